#!/usr/bin/env python3
"""A small regression sweep: the recorded logs under two sensor models and three seeds, run as
mote.replay tasks on dask workers, printed as one table and written to sweep.csv.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep_logs.py ../shared/data
    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep_logs.py ../shared/data \\
        tcp://scheduler-host:8786

Without an address it starts a LocalCluster on this machine (one single-threaded worker process
per core). With one, every worker must be able to `import mote` and read DATA_DIR at the same
path: start them as `PYTHONPATH=.../build/python dask worker tcp://scheduler-host:8786
--nthreads 1`.
"""

import csv
import pathlib
import sys

import mote


def main(data, scheduler):
    logs = {
        "intel": {"map": data / "intel/intel.yaml", "log": data / "intel/intel.clf",
                  "reference": data / "intel/intel.gt.tum"},
        "wean": {"map": data / "wean/wean_map.yaml", "log": data / "wean/robotdata1.clf"},
        "dis": {"map": data / "dis/dis_underground.yaml", "log": data / "dis/dis-underground.bag"},
    }
    configs = {"field": mote.LocalizerConfig(max_particles=5000),
               "beam": mote.LocalizerConfig(max_particles=5000,
                                            laser_model_type=mote.LaserModel.BEAM)}
    rows = mote.sweep(logs, configs, client=scheduler, seed=[1, 2, 3])

    def num(value, digits):
        return "-" if value is None else f"{value:.{digits}f}"

    print(f"{'log':6} {'config':6} {'seed':>4} {'ATE m':>7} {'head deg':>8} {'update ms':>9} "
          f"{'particles':>9} {'updates':>7}")
    for r in rows:
        print(f"{r.log:6} {r.config:6} {r.seed:4} {num(r.ate_rmse_m, 4):>7} "
              f"{num(r.heading_rmse_deg, 3):>8} {num(r.update_ms, 2):>9} "
              f"{num(r.particles, 0):>9} {r.updates:7}")
    with open("sweep.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(mote.SweepRow._fields)
        writer.writerows(rows)


if __name__ == "__main__":  # dask's worker processes import this file again: no work at import
    if len(sys.argv) not in (2, 3):
        sys.exit(f"usage: {sys.argv[0]} DATA_DIR [SCHEDULER_ADDRESS]")
    main(pathlib.Path(sys.argv[1]), sys.argv[2] if len(sys.argv) == 3 else None)
