#!/usr/bin/env python3
"""Tracks the Intel log from its reference start, reads the particles as NumPy views and
replays the log through mote replay (ctest runs it as python_example_track).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/track.py [DATA_DIR]

DATA_DIR defaults to ../shared/data; without the Intel log there it says so and exits 1.
"""

import os
import sys

import numpy as np

import mote

data = sys.argv[1] if len(sys.argv) > 1 else "../shared/data"
d = data + "/intel/"
if not os.path.exists(d + "intel.yaml"):
    sys.exit(f"track.py: {d}intel.yaml not found: give the recorded data's folder")
grid = mote.load_map(d + "intel.yaml")
loc = mote.Localizer(grid, mote.LocalizerConfig(min_particles=2000, max_particles=2000))
loc.initialize((0.60, -0.03, -0.355), np.diag([0.01, 0.01, 0.0076]))  # reference start
for stamp, odom, scan in mote.open_log(d + "intel.clf"):
    loc.update(odom, scan)
p = loc.particles  # x, y, theta, log_weight: zero-copy float32 views
print(loc.estimate.refined.pose, len(p), p.x.flags.owndata, p.x.flags.writeable)
print(loc.last_update.state)  # LocalizationState.TRACKING, UNCERTAIN or LOST
print(f"last update {loc.last_update.ms.total:.2f} ms, "
      f"ESS {loc.last_update.effective_sample_size:.0f}")
r = mote.replay(map=d + "intel.yaml", log=d + "intel.clf", reference=d + "intel.gt.tum",
                particles=2000)
print(f"ATE {r['ate_rmse_m']:.4f} m, heading {r['heading_rmse_deg']:.3f} deg, "
      f"{r['updates']} updates")
