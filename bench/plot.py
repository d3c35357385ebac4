#!/usr/bin/env python3
"""Turns bench/results/bench_e2e.json (Google Benchmark JSON) into the results table e2e.md and
the plot e2e.png that BENCHMARKS.md shows.

Usage: bench/plot.py [RESULTS_DIR]   (default: bench/results next to this script)

Medians are used when the run had repetitions (--benchmark_repetitions=N with aggregates);
a run without repetitions is tabled from its single measurements and says so.
"""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

NAME = re.compile(
    r"BM_Localizer_Update/(?P<model>[a-z_]+)/(?P<setting>[a-z]+)/n:(?P<n>\d+)"
    r"/beams:(?P<beams>\d+)/threads:(?P<threads>\d+)")

MACHINE = re.compile(
    r"BM_Machine_(?P<loop>[A-Za-z]+)/(?P<when>[a-z]+)/threads:(?P<threads>\d+)")

MODELS = {"likelihood_field": "likelihood field", "beam": "beam model"}
COLORS = {"likelihood_field": "tab:blue", "beam": "tab:red"}

# The targets of issue 7, for 2 threads.
LF_100K_TRACKING_MS = 8.0
LF_1M_MS = 66.0  # 15 Hz
BEAM_10K_RAYS_PER_S = 20e6
MIN_SPEEDUP = 1.8
# Issue 19's targets for the beam model's range table (tracking, 60 beams, 2 threads).
TABLE_RAYS_PER_S = {10_000: 150e6, 100_000: 100e6}
RAY_CASTING = re.compile(r"BM_Localizer_Update/beam/tracking/n:(?P<n>\d+)/beams:60/threads:2"
                         r"/ray_casting:(?P<mode>[a-z_]+)")


def load_cases(path):
    """The run's context, {(model, setting, n, beams, threads): entry},
    {(loop, when, threads): entry} for the machine check, and whether the entries are medians."""
    data = json.loads(path.read_text())
    entries = data.get("benchmarks", [])
    medians = [e for e in entries if e.get("aggregate_name") == "median"]
    chosen = medians if medians else [e for e in entries if e.get("run_type") == "iteration"]
    cases, machine = {}, {}
    for e in chosen:
        name = e.get("run_name", e["name"])
        if (e.get("error_occurred") or "/defaults:" in name or "/kld_min:" in name
                or "/ray_casting:" in name):
            continue  # the mote-vs-nav2 and exact-vs-table pairs are read from the JSON directly
        if (m := NAME.match(name)) is not None:
            key = (m["model"], m["setting"], int(m["n"]), int(m["beams"]), int(m["threads"]))
            cases[key] = e
        elif (m := MACHINE.match(name)) is not None:
            machine[(m["loop"], m["when"], int(m["threads"]))] = e
    return data.get("context", {}), cases, machine, bool(medians)


def ms(entry):
    """Real time of one update in ms, whatever unit the run reported in."""
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[entry.get("time_unit", "ns")]
    return entry["real_time"] * scale


def si(value):
    for factor, suffix in ((1e9, " G"), (1e6, " M"), (1e3, " k")):
        if value >= factor:
            return f"{value / factor:.3g}{suffix}"
    return f"{value:.3g}"


def num(value):
    """3 significant digits without an exponent (1,330 rather than 1.33e+03)."""
    return f"{value:,.0f}" if value >= 1000 else f"{value:.3g}"


def verdict(ok):
    return "met" if ok else "**not met**"


def cpu_model():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def targets_for(key, cases):
    """The issue 7 targets that apply to one row, as text."""
    model, setting, n, beams, threads = key
    two = cases.get((model, setting, n, beams, 2))
    one = cases.get((model, setting, n, beams, 1))
    out = []
    if two is not None and beams == 60:
        if model == "likelihood_field" and n == 100_000 and setting == "tracking":
            out.append(f"< {LF_100K_TRACKING_MS:g} ms: {verdict(ms(two) < LF_100K_TRACKING_MS)}")
        if model == "likelihood_field" and n == 1_000_000:
            out.append(f"< {LF_1M_MS:g} ms: {verdict(ms(two) < LF_1M_MS)}")
        if model == "beam" and n == 10_000:
            rays = two.get("rays/s", 0.0)
            out.append(f"> 20 M rays/s: {verdict(rays > BEAM_10K_RAYS_PER_S)}")
    if one is not None and two is not None and n > 10_000:
        out.append(f"2t/1t >= {MIN_SPEEDUP}: {verdict(ms(one) / ms(two) >= MIN_SPEEDUP)}")
    return "; ".join(out)


def summary(cases):
    """One line per issue 7 target, from the 2-thread medians."""
    def get(model, setting, n, threads=2):
        return cases.get((model, setting, n, 60, threads))

    lines = ["| target (2 threads) | measured | |", "|---|---|---|"]
    lf = get("likelihood_field", "tracking", 100_000)
    if lf:
        lines.append(f"| likelihood field, 100k, 60 beams, tracking: < {LF_100K_TRACKING_MS:g} ms "
                     f"| {ms(lf):.3g} ms | {verdict(ms(lf) < LF_100K_TRACKING_MS)} |")
    for setting in ("tracking", "global"):
        if e := get("likelihood_field", setting, 1_000_000):
            lines.append(f"| likelihood field, 1M, 60 beams, {setting}: < {LF_1M_MS:g} ms "
                         f"| {ms(e):.3g} ms | {verdict(ms(e) < LF_1M_MS)} |")
    for setting in ("tracking", "global"):
        if e := get("beam", setting, 10_000):
            lines.append(f"| beam model, 10k, 60 beams, {setting}: > 20 M rays/s "
                         f"| {si(e['rays/s'])} rays/s | {verdict(e['rays/s'] > BEAM_10K_RAYS_PER_S)} |")
    ratios = sorted((ms(cases[k[:4] + (1,)]) / ms(e), k) for k, e in cases.items()
                    if k[4] == 2 and k[2] > 10_000 and k[:4] + (1,) in cases)
    if ratios:
        met = sum(r >= MIN_SPEEDUP for r, _ in ratios)
        worst, key = ratios[0]
        lines.append(f"| 2t/1t >= {MIN_SPEEDUP} on every case over 10k particles "
                     f"| {met} of {len(ratios)} cases; lowest {worst:.2f} "
                     f"({MODELS[key[0]]}, {key[1]}, {key[2]:,}, {key[3]} beams), "
                     f"median {ratios[len(ratios) // 2][0]:.2f} "
                     f"| {verdict(met == len(ratios))} |")
    return lines if len(lines) > 2 else []


def rows(cases):
    keys = sorted({k[:4] for k in cases},
                  key=lambda k: (list(MODELS).index(k[0]), k[1] != "tracking", k[2], k[3]))
    lines = [
        "| model | setting | particles | beams | ms/update 1t | ms/update 2t | updates/s 2t "
        "| particle-beams/s 2t | 2t/1t | target (2 threads) |",
        "|---|---|--:|--:|--:|--:|--:|--:|--:|---|",
    ]
    for model, setting, n, beams in keys:
        one = cases.get((model, setting, n, beams, 1))
        two = cases.get((model, setting, n, beams, 2))
        ratio = f"{ms(one) / ms(two):.2f}" if one and two else "-"
        lines.append(
            f"| {MODELS[model]} | {setting} | {n:,} | {beams} "
            f"| {num(ms(one)) if one else '-'} | {num(ms(two)) if two else '-'} "
            f"| {si(two['updates/s']) if two else '-'} "
            f"| {si(two['particle_beams/s']) if two else '-'} | {ratio} "
            f"| {targets_for((model, setting, n, beams, 2), cases)} |")
    return lines


def ray_casting_cases(path):
    """{(particles, mode): entry} of the beam model's ray-casting cases, medians when the run
    has them (as load_cases), else single iterations."""
    entries = json.loads(path.read_text()).get("benchmarks", [])
    medians = [e for e in entries if e.get("aggregate_name") == "median"]
    chosen = medians if medians else [e for e in entries if e.get("run_type") == "iteration"]
    out = {}
    for e in chosen:
        m = RAY_CASTING.match(e.get("run_name", e["name"]))
        if m is not None and not e.get("error_occurred") and "rays/s" in e:
            out[(int(m["n"]), m["mode"])] = e
    return out


def ray_casting_rows(found):
    """Exact casting against the range table, with issue 19's targets; the table's accuracy is
    not measured here (BENCHMARKS.md, "Range table")."""
    modes = ("exact", "table")
    lines = ["| particles | " + " | ".join(f"{m}: rays/s" for m in modes) + " | issue 19 target |",
             "|--:|" + "--:|" * len(modes) + "---|"]
    for n in sorted({k[0] for k in found}):
        rays = {m: found[(n, m)]["rays/s"] for m in modes if (n, m) in found}
        target = TABLE_RAYS_PER_S.get(n)
        verdicts = "; ".join(f"{m}: {verdict(r > target)}" for m, r in rays.items()
                             if target and m != "exact")
        lines.append(f"| {n:,} | " + " | ".join(si(rays[m]) if m in rays else "-" for m in modes)
                     + (f" | > {si(target)}: {verdicts} |" if target else " | |"))
    return lines


def phase_rows(cases):
    """ns per particle per phase, tracking, 60 beams, 2 threads."""
    phases = ["motion", "sensor", "normalize", "resample", "estimate"]
    lines = ["| model | particles | " + " | ".join(phases) + " | bytes/particle |",
             "|---|--:|" + "--:|" * len(phases) + "--:|"]
    for (model, setting, n, beams, threads), e in sorted(
            cases.items(), key=lambda kv: (list(MODELS).index(kv[0][0]), kv[0][2])):
        if setting != "tracking" or beams != 60 or threads != 2:
            continue
        values = " | ".join(num(e[f"ns_{p}/p"]) for p in phases)
        lines.append(f"| {MODELS[model]} | {n:,} | {values} | {e['bytes/p']:.1f} |")
    return lines


def source_version(results):
    """The commit the benchmarked tree was at, "-dirty" when it had uncommitted changes, as
    `make bench` recorded it (else the tree this script is in, now)."""
    recorded = results / "version.txt"
    if recorded.exists():
        return recorded.read_text().strip()
    try:
        out = subprocess.run(["git", "describe", "--always", "--dirty"], capture_output=True,
                             text=True, cwd=Path(__file__).parent, check=True)
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def machine_lines(context, results, medians):
    uptime = results / "uptime.txt"
    load = uptime.read_text().strip().splitlines() if uptime.exists() else []
    lines = [
        f"- CPU: {cpu_model()}, {context.get('num_cpus', os.cpu_count())} cores "
        f"({context.get('mhz_per_cpu', '?')} MHz)",
        f"- map: {context.get('map', '?')}; run {context.get('date', '?')} "
        f"on mote {source_version(results)}",
        "- `uptime` before and after the run:" if load else "- `uptime`: not recorded",
    ]
    lines += [f"  - `{line.strip()}`" for line in load]
    lines.append("- values: " + ("medians of the repetitions" if medians
                                 else "single measurements (no repetitions)"))
    return lines


def loop_ratios(machine, loop):
    """One machine-check loop's 2-thread/1-thread ratio at the start and end of the run."""
    return [f"{ms(machine[(loop, when, 1)]) / ms(machine[(loop, when, 2)]):.2f} at the {when}"
            for when in ("start", "end")
            if (loop, when, 1) in machine and (loop, when, 2) in machine]


def machine_check(machine):
    """The machine-check loops' 2-thread/1-thread ratios."""
    compute, vector = loop_ratios(machine, "ComputeLoop"), loop_ratios(machine, "VectorLoop")
    if not compute and not vector:
        return []
    lines = ["- machine check, 2 threads / 1 thread (below 2, other processes held a core, and "
             "no case's 2t/1t ratio can exceed what the machine gave):"]
    if compute:
        lines.append(f"  - BM_Machine_ComputeLoop (latency-bound): {', '.join(compute)}")
    if vector:
        lines.append(f"  - BM_Machine_VectorLoop (vector-throughput-bound; lower than the "
                     f"compute loop means the threads share one core's vector units): "
                     f"{', '.join(vector)}")
    return lines


def write_table(path, context, cases, machine, medians, results, ray_casting):
    text = ["# End-to-end Localizer update (bench_e2e)", ""]
    text += machine_lines(context, results, medians)
    text += machine_check(machine)
    text += ["", "One full update (motion, sensor, normalize, resample, estimate) per iteration, "
             "real time. 1t / 2t: the Localizer's thread option.", ""]
    if targets := summary(cases):
        text += ["## Targets", ""] + targets + ["", "## All cases", ""]
    text += rows(cases)
    phases = phase_rows(cases)
    if len(phases) > 2:
        text += ["", "## ns per particle per phase (tracking, 60 beams, 2 threads)", ""] + phases
    if ray_casting:
        text += ["", "## Beam model: exact casting against the range table (tracking, 60 beams, "
                 "2 threads)", "", "Accuracy against exact casting: "
                 "BENCHMARKS.md, \"Range table\".", ""]
        text += ray_casting_rows(ray_casting)
    path.write_text("\n".join(text) + "\n")


def write_plot(path, cases):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for model in MODELS:
        for threads, style in ((1, "--"), (2, "-")):
            points = sorted((k[2], ms(e)) for k, e in cases.items()
                            if k[0] == model and k[1] == "tracking" and k[3] == 60
                            and k[4] == threads)
            if points:
                ax.plot([p[0] for p in points], [p[1] for p in points], style, marker="o",
                        color=COLORS[model],
                        label=f"{MODELS[model]}, {threads} thread{'s' if threads > 1 else ''}")
    ax.axhline(LF_1M_MS, color="grey", linewidth=0.8, linestyle=":")
    ax.text(1e3, LF_1M_MS * 1.1, "66 ms (15 Hz)", color="grey", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("particles")
    ax.set_ylabel("ms per update (median)")
    ax.set_title("Localizer update, tracking, 60 beams")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    results = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent / "results"
    source = results / "bench_e2e.json"
    if not source.exists():
        sys.exit(f"plot.py: {source}: not found (run `make bench` first)")
    context, cases, machine, medians = load_cases(source)
    if not cases:
        sys.exit(f"plot.py: {source}: no BM_Localizer_Update results (BENCH_FILTER?)")
    write_table(results / "e2e.md", context, cases, machine, medians, results,
                ray_casting_cases(source))
    write_plot(results / "e2e.png", cases)
    print(f"plot.py: wrote {results / 'e2e.md'} and {results / 'e2e.png'}")


if __name__ == "__main__":
    main()
