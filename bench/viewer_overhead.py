#!/usr/bin/python3
"""What `mote replay --viewer` costs on the Intel log (issue 20: under 5% of the replay's time).

Runs `mote replay` without and with --viewer, interleaved (the machine is noisy), and prints the
medians of the whole command's wall time, its CPU time (user + system: less disturbed by other
processes than wall time, but it counts worker threads' spinning; exact with --threads 1) and
report.json's wall_s (the replay loop, which holds the recording but not the writing of
viewer.html). With --baseline MOTE, a build without
the viewer runs in the same rotation, for "nothing when --viewer is off".

  bench/viewer_overhead.py --mote build/tool/mote [--baseline OTHER/mote] [--runs 9]
                           [-- extra replay flags, e.g. --particles 5000]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time


def run(mote, data, out, extra):
    intel = os.path.join(data, "intel")
    cmd = [mote, "replay", "--map", os.path.join(intel, "intel.yaml"),
           "--log", os.path.join(intel, "intel.clf"),
           "--reference", os.path.join(intel, "intel.gt.tum"), "--out", out, "--quiet", *extra]
    start = time.perf_counter()
    child = subprocess.Popen(cmd)
    _, status, usage = os.wait4(child.pid, 0)
    seconds = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({child.returncode})")
    with open(os.path.join(out, "report.json")) as f:
        return seconds, usage.ru_utime + usage.ru_stime, json.load(f)["wall_s"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mote", required=True)
    parser.add_argument("--baseline", help="a mote built without the viewer")
    parser.add_argument("--data", default=os.path.join(os.path.dirname(__file__),
                                                       "../../shared/data"))
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("extra", nargs="*", help="flags for every run")
    args = parser.parse_args()
    variants = [("off", args.mote, []), ("--viewer", args.mote, ["--viewer"])]
    if args.baseline:
        variants.insert(0, ("baseline", args.baseline, []))
    times = {name: ([], [], []) for name, _, _ in variants}
    with tempfile.TemporaryDirectory(prefix="mote_viewer_bench_") as work:
        for _ in range(args.runs):
            for name, mote, flags in variants:
                measured = run(mote, args.data, os.path.join(work, name.strip("-")),
                               flags + args.extra)
                for column, value in zip(times[name], measured):
                    column.append(value)
    reference = [statistics.median(column) for column in times["off"]]
    print(f"Intel log, {args.runs} interleaved runs each, flags: {' '.join(args.extra) or '-'}")
    print(f"{'variant':10}" + "".join(f" {h:>10} {'vs off':>7}"
                                      for h in ("command s", "cpu s", "loop s")))
    for name, columns in times.items():
        line = f"{name:10}"
        for column, ref in zip(columns, reference):
            m = statistics.median(column)
            line += f" {m:10.3f} {m / ref - 1:+7.1%}"
        print(line)


if __name__ == "__main__":
    main()
