#!/usr/bin/python3
"""What `mote replay --viewer` costs on the Intel log (issue 20: under 5% of the replay's time).

Runs `mote replay` without and with --viewer, interleaved (the machine is noisy), and prints the
medians of the whole command's wall time and of report.json's wall_s (the replay loop, which
holds the recording but not the writing of viewer.html). With --baseline MOTE, a build without
the viewer runs in the same rotation, for "nothing when --viewer is off".

  bench/viewer_overhead.py --mote build/replay/mote [--baseline OTHER/mote] [--runs 9]
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
    subprocess.run(cmd, check=True)
    seconds = time.perf_counter() - start
    with open(os.path.join(out, "report.json")) as f:
        return seconds, json.load(f)["wall_s"]


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
    times = {name: ([], []) for name, _, _ in variants}
    with tempfile.TemporaryDirectory(prefix="mote_viewer_bench_") as work:
        for _ in range(args.runs):
            for name, mote, flags in variants:
                command_s, loop_s = run(mote, args.data, os.path.join(work, name.strip("-")),
                                        flags + args.extra)
                times[name][0].append(command_s)
                times[name][1].append(loop_s)
    ref_cmd, ref_loop = (statistics.median(t) for t in times["off"])
    print(f"Intel log, {args.runs} interleaved runs each, flags: {' '.join(args.extra) or '-'}")
    print(f"{'variant':10} {'command s':>10} {'vs off':>8} {'loop s':>8} {'vs off':>8}")
    for name, (command_s, loop_s) in times.items():
        c, lo = statistics.median(command_s), statistics.median(loop_s)
        print(f"{name:10} {c:10.3f} {c / ref_cmd - 1:+8.1%} {lo:8.3f} {lo / ref_loop - 1:+8.1%}")


if __name__ == "__main__":
    main()
