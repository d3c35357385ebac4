"""mote: Monte Carlo localization on 2D occupancy grids, at C++ speed.

    import mote
    grid = mote.load_map("intel.yaml")
    loc = mote.Localizer(grid, mote.LocalizerConfig(max_particles=5000))
    loc.initialize_global()
    for stamp, odom, scan in mote.open_log("intel.clf"):
        loc.update(odom, scan)
    print(loc.estimate.best.mean, loc.particles.x)   # x: a zero-copy NumPy view
    rows = mote.sweep([{"map": "intel.yaml", "log": "intel.clf"}], [None, {"max_particles": 2000}])
"""

from ._mote import *  # noqa: F401,F403
from ._mote import __doc__ as _native_doc  # noqa: F401
from ._sweep import SweepRow, sweep  # noqa: F401  (imports dask only when sweep() runs)

__all__ = [name for name in dir() if not name.startswith("_")]
