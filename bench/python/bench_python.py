#!/usr/bin/env python3
"""What the Python package costs over the C++ Localizer (issue 18), with timeit's clock.

  PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_python.py [DATA_DIR] [OUT.json]

1. update() overhead: the Intel log at 10k particles x 60 beams, the wall time of each
   Localizer.update() call from Python against the C++ update's own ms.total (UpdateStats),
   medians over the updates that ran; the overhead is their difference.
2. Reading the particles at 1M: the time to take the x, y, theta, log_weight views (no copy:
   np.shares_memory with a second view, owndata False) against particles.copy().
Prints one line per measurement and writes them as JSON when OUT is given.
"""
import json
import statistics
import sys
import timeit

import numpy as np

import mote

clock = timeit.default_timer


def update_overhead(data):
    grid = mote.load_map(f"{data}/intel/intel.yaml")
    config = mote.LocalizerConfig(min_particles=10000, max_particles=10000, max_beams=60)
    localizer = mote.Localizer(grid, config)
    localizer.initialize((0.600266, -0.032033, -0.354665), np.diag([0.01, 0.01, 0.0076]))
    wall, cpp = [], []
    for _stamp, odometry, scan in mote.open_log(f"{data}/intel/intel.clf"):
        start = clock()
        localizer.update(odometry, scan)
        elapsed_ms = (clock() - start) * 1e3
        if localizer.last_update.ran:
            wall.append(elapsed_ms)
            cpp.append(localizer.last_update.ms.total)
    w, c = statistics.median(wall), statistics.median(cpp)
    return {"updates": len(wall), "python_ms": w, "cpp_ms": c,
            "overhead_us": (w - c) * 1e3, "overhead_percent": 100.0 * (w - c) / c}


def particle_views(data):
    grid = mote.load_map(f"{data}/intel/intel.yaml")
    n = 1_000_000
    config = mote.LocalizerConfig(min_particles=n, max_particles=n)
    localizer = mote.Localizer(grid, config)
    localizer.initialize((0.600266, -0.032033, -0.354665), np.diag([0.01, 0.01, 0.0076]))

    def views():
        p = localizer.particles
        return p.x, p.y, p.theta, p.log_weight

    x = views()[0]
    shared = np.shares_memory(x, localizer.particles.x) and not x.flags.owndata
    reps = 20
    view_s = timeit.timeit(views, number=reps) / reps
    copy_s = timeit.timeit(lambda: localizer.particles.copy(), number=3) / 3
    return {"particles": len(x), "zero_copy": bool(shared), "views_us": view_s * 1e6,
            "copy_ms": copy_s * 1e3}


def main():
    data = sys.argv[1] if len(sys.argv) > 1 else "../shared/data"
    results = {"update_10k_x_60": update_overhead(data), "particles_1M": particle_views(data)}
    u, p = results["update_10k_x_60"], results["particles_1M"]
    print(f"update() at 10k x 60, {u['updates']} updates: Python {u['python_ms']:.3f} ms, "
          f"C++ {u['cpp_ms']:.3f} ms, overhead {u['overhead_us']:.1f} us "
          f"({u['overhead_percent']:.2f}%)")
    print(f"particles at 1M: four views in {p['views_us']:.1f} us (zero copy: {p['zero_copy']}), "
          f"particles.copy() {p['copy_ms']:.2f} ms")
    if len(sys.argv) > 2:
        with open(sys.argv[2], "w") as out:
            json.dump(results, out, indent=2)


if __name__ == "__main__":
    main()
