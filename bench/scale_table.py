#!/usr/bin/env python3
"""The table of bench/README.md's "Speed and memory at scale": the derivations, the context
signal and the grid through the engine on 1 and 2 threads, beside the hand-written
baselines of the same run and lpfg's figures, and the peak memory of Koch at n = 10.

    python3 bench/scale_table.py [BUILD_DIR]          (default build/)

Needs a Release build with ONTOGEN_BUILD_BENCH=ON (bench/README.md). The suite runs three
times; each time is the lowest of its three runs' medians of 3 repetitions of wall time
(on a shared machine the others' load only adds time, and a single run's ratios moved by a
third). The load average before and after is printed with them. lpfg is not built here: its
figures are those measured beside ontogen on this kind of machine (2-core, 2026-11-22).
"""

import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "build")
BENCH = os.path.join(BUILD, "bench", "ontogen_bench")
ONTOGEN = os.path.join(BUILD, "apps", "ontogen")

# workload: (engine benchmark without its thread argument, hand-written benchmark, lpfg seconds)
WORKLOADS = [
    ("Koch, n = 10", "BM_KochFromAxiom/10", "BM_KochHandWritten/10", 0.253),
    ("Thue-Morse, n = 24", "BM_ThueMorseFromAxiom/24", "BM_ThueMorseHandWritten/24", 1.288),
    ("Parametric, n = 20", "BM_ParametricFromAxiom/20", "BM_ParametricHandWritten/20", 0.089),
    ("Context signal, 100,000 x 1,000", "BM_ContextSignal/1000", "BM_ContextSignalHandWritten/1000", 6.51),
    ("Grid diffusion 1000^2, RK4, 4 steps", "BM_GridDiffusionThroughRate", "BM_GridDiffusionHandWritten", None),
]
LPFG_KOCH_PEAK_MIB = 110


def load_average():
    with open("/proc/loadavg") as f:
        return f.read().split()[0]


RUNS = 3


def run_benchmarks():
    names = [w[1] for w in WORKLOADS] + [w[2] for w in WORKLOADS] + ["BM_KochCompactWord/10"]
    pattern = "^(" + "|".join(names) + ")(/|$)"
    lowest = {}
    for _ in range(RUNS):
        with tempfile.NamedTemporaryFile(suffix=".json") as out:
            subprocess.run([BENCH, "--benchmark_filter=" + pattern, "--benchmark_repetitions=3",
                            "--benchmark_report_aggregates_only=true", "--benchmark_out=" + out.name,
                            "--benchmark_out_format=json"], check=True, stdout=subprocess.DEVNULL)
            report = json.load(open(out.name))
        for b in report["benchmarks"]:
            if b.get("aggregate_name") != "median":
                continue
            name = b["run_name"].split("/iterations:")[0].removesuffix("/real_time")
            scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
            wall = b["real_time"] * scale
            lowest[name] = min(wall, lowest.get(name, wall))
    return lowest


def peak_kib(arguments):
    result = subprocess.run(["/usr/bin/time", "-f", "%M"] + arguments, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, check=True)
    return int(result.stderr.strip().splitlines()[-1])


def seconds(value):
    return "-" if value is None else f"{value:.4f}"


def ratio(a, b):
    return "-" if a is None or b is None else f"{a / b:.2f}"


def main():
    before = load_average()
    medians = run_benchmarks()
    koch = os.path.join(ROOT, "models", "koch.cell")
    peaks = {t: peak_kib([ONTOGEN, "run", koch, "--until", "10", "--format", "none", "--stats", "--threads", str(t)])
             for t in (1, 2)}
    word_peak = peak_kib([ONTOGEN, "word", koch, "--at", "10"])
    after = load_average()

    print(f"Load average {before} before, {after} after. Wall seconds: the lowest of {RUNS} runs' medians "
          f"of 3 repetitions.\n")
    print("| workload | lpfg | ontogen, 1 thread | ontogen, 2 threads | hand-written | ontogen / lpfg "
          "| ontogen / hand-written (1 thread) | 2 threads / 1 |")
    print("|---|---|---|---|---|---|---|---|")
    for title, engine, hand, lpfg in WORKLOADS:
        one = medians.get(engine + "/1")
        two = medians.get(engine + "/2", medians.get(engine + "/0"))
        hand_seconds = medians.get(hand)
        best = min(v for v in (one, two) if v is not None) if (one or two) else None
        print(f"| {title} | {seconds(lpfg)} | {seconds(one)} | {seconds(two)} | {seconds(hand_seconds)} "
              f"| {ratio(best, lpfg)} | {ratio(one, hand_seconds)} | {ratio(one, two)} |")
    compact = [medians.get(f"BM_KochCompactWord/10/{t}") for t in (0, 1, 2)]
    print(f"\nKoch, n = 10, in the compact word alone (BM_KochCompactWord): serial {seconds(compact[0])} s, "
          f"by slices on 1 thread {seconds(compact[1])} s, on 2 threads {seconds(compact[2])} s; "
          f"hand-written bytes {seconds(medians.get('BM_KochHandWritten/10'))} s.")
    print(f"\nPeak memory, Koch n = 10 (`ontogen run models/koch.cell --until 10 --format none --stats`): "
          f"{peaks[1] / 1024:.1f} MiB on 1 thread, {peaks[2] / 1024:.1f} MiB on 2; lpfg {LPFG_KOCH_PEAK_MIB} MiB; "
          f"`ontogen word --at 10`: {word_peak / 1024:.1f} MiB.")


if __name__ == "__main__":
    main()
