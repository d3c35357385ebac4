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

import functools as _functools
import re as _re

from ._mote import *  # noqa: F401,F403
from ._mote import __doc__ as _native_doc  # noqa: F401
from ._mote import _closest_word
from ._sweep import SweepRow, sweep  # noqa: F401  (imports dask only when sweep() runs)


def _with_keyword_hints(fn):
    """fn, raising "f() got an unexpected keyword argument 'partcles' (did you mean
    'particles'?)" for a misspelled keyword, where pybind11 lists every signature instead."""
    head = (fn.__doc__ or "").split("\n", 1)[0]  # pybind11's "name(a: int, *, b: str = ...) -> T"
    names = _re.findall(r"[(,]\s*(\w+)\s*:", head) if head.startswith(fn.__name__ + "(") else []
    if not names:
        return fn

    @_functools.wraps(fn)
    def call(*args, **kwargs):
        for key in kwargs:
            if key not in names:
                near = _closest_word(key, names)
                hint = f" (did you mean '{near}'?)" if near else ""
                raise TypeError(f"{fn.__name__}() got an unexpected keyword argument '{key}'{hint}")
        return fn(*args, **kwargs)

    call.__module__, call.__qualname__ = __name__, fn.__name__  # mote.replay, picklable by name
    return call


replay = _with_keyword_hints(replay)  # noqa: F405
open_log = _with_keyword_hints(open_log)  # noqa: F405
load_config = _with_keyword_hints(load_config)  # noqa: F405
config_yaml = _with_keyword_hints(config_yaml)  # noqa: F405
load_map = _with_keyword_hints(load_map)  # noqa: F405

__all__ = [name for name in dir() if not name.startswith("_")]
