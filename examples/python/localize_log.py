#!/usr/bin/env python3
"""examples/01 in Python: localize globally on a recorded log, print the estimate every 50
updates, and plot the trajectory and the final particles over the map with matplotlib.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/localize_log.py \\
        ../shared/data/intel/intel.yaml ../shared/data/intel/intel.clf intel.png
"""

import sys

import matplotlib

matplotlib.use("Agg")  # write a file; no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mote  # noqa: E402


def localize(grid, log_path):
    """The update loop of examples/01: returns the (x, y) trajectory and the final particles."""
    loc = mote.Localizer(grid, mote.LocalizerConfig(max_particles=20000))
    loc.initialize_global()
    trajectory, updates = [], 0
    for stamp, odom, scan in mote.open_log(log_path):
        if not loc.update(odom, scan):
            continue
        best = loc.estimate.refined.pose  # the heaviest hypothesis matched to the map
        trajectory.append((best.x, best.y))
        updates += 1
        if updates % 50 == 0:
            u = loc.last_update
            print(f"t={stamp:.1f} s  x={best.x:.2f} y={best.y:.2f} theta={best.theta:.2f}  "
                  f"{u.state.name.lower()}  particles={u.particles}  update={u.ms.total:.2f} ms")
    return np.array(trajectory), loc.particles.copy()


def plot(grid, trajectory, particles, out):
    """The map (row 0 at the bottom), the estimate and the final particle cloud, in metres."""
    o, r = grid.origin, grid.resolution
    extent = (o.x, o.x + grid.width * r, o.y, o.y + grid.height * r)
    shade = np.choose(grid.cells, [1.0, 0.0, 0.7])  # free white, occupied black, unknown grey
    fig, ax = plt.subplots(figsize=(8, 8))
    ax.imshow(shade, cmap="gray", vmin=0, vmax=1, origin="lower", extent=extent)
    ax.plot(trajectory[:, 0], trajectory[:, 1], "r-", lw=0.8, label="estimate")
    ax.scatter(particles.x, particles.y, s=1, c="b", label="final particles")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="upper right")
    fig.savefig(out, dpi=120, bbox_inches="tight")


def main(argv):
    if len(argv) != 4:
        print(f"usage: {argv[0]} MAP.yaml LOG OUT.png", file=sys.stderr)
        return 2
    try:
        grid = mote.load_map(argv[1])
        trajectory, particles = localize(grid, argv[2])
    except mote.Error as e:
        print(e, file=sys.stderr)
        return 1
    plot(grid, trajectory, particles, argv[3])
    print(f"wrote {argv[3]}: {len(trajectory)} updates, {len(particles)} particles")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
