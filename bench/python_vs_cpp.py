#!/usr/bin/env python3
"""Koch's curve grown to n = 10 (19,531,249 modules) and read as columns, from Python
(ontogen.compile, World.advance, World.arrays: numpy arrays) and through the C++ API
(bench/python_vs_cpp_baseline.cpp: compileSource, World::advanceTo, visitWord into
vectors), side by side in one run, and through L-Py's documented API where it is
installed (openalea.lpy: Lsystem.derive, then the lstring read module by module).

Each repetition of each side runs in a fresh process, so that neither finds the
other's memory to reuse; the table gives the median and the fastest of each phase in
processor seconds, user and system, of the process (on a shared machine wall time
mostly measures the others; one thread unless --threads says otherwise).

    python3 bench/python_vs_cpp.py [--build build] [--until 10] [--repetitions 5] [--threads 1]

Needs a build with -DONTOGEN_PYTHON=ON -DONTOGEN_BUILD_BENCH=ON (targets ontogen_python
and python_vs_cpp_baseline). Not a test: the machine's load moves the figures.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KOCH = os.path.join(ROOT, "models", "koch.cell")


def python_side(until, threads):
    """One repetition in this process: what a Python user writes (numpy imported first,
    as by anyone who reads arrays: pybind11 imports it at the first array otherwise)."""
    import numpy  # noqa: F401
    import ontogen
    start = time.process_time()
    world = ontogen.load(KOCH).world(seed=0, threads=threads)
    world.advance(until)
    grow = time.process_time() - start
    start = time.process_time()
    arrays = world.arrays()
    read = time.process_time() - start
    return {"grow": grow, "read": read, "cells": int(arrays["id"].shape[0]), "labels": len(arrays["labels"])}


def lpy_side(until):
    """One repetition through L-Py's documented API, or None where it is not installed."""
    try:
        from openalea.lpy import Lsystem
    except ImportError:
        return None
    code = "Axiom: F\nderivation length: %d\nproduction:\nF --> F+F-F-F+F\nendlsystem\n" % int(until)
    start = time.process_time()
    lsystem = Lsystem()
    lsystem.setCode(code)
    lstring = lsystem.derive()
    grow = time.process_time() - start
    start = time.process_time()
    names = [module.name for module in lstring]
    read = time.process_time() - start
    return {"grow": grow, "read": read, "cells": len(names), "labels": len(set(names))}


def run_side(command, env=None):
    done = subprocess.run(command, check=True, capture_output=True, text=True, env=env)
    return [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--until", type=float, default=10)
    parser.add_argument("--repetitions", type=int, default=5)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--side", choices=("python", "lpy"), help=argparse.SUPPRESS)
    args = parser.parse_args()

    if args.side == "python":
        print(json.dumps(python_side(args.until, args.threads)))
        return 0
    if args.side == "lpy":
        result = lpy_side(args.until)
        print(json.dumps(result) if result else "")
        return 0

    build = os.path.abspath(args.build)
    baseline = os.path.join(build, "bench", "python_vs_cpp_baseline")
    if not os.path.exists(baseline) or not os.path.isdir(os.path.join(build, "python", "ontogen")):
        sys.exit(f"python_vs_cpp: build {build} with -DONTOGEN_PYTHON=ON -DONTOGEN_BUILD_BENCH=ON "
                 "(targets ontogen_python python_vs_cpp_baseline)")
    env = dict(os.environ, PYTHONPATH=os.path.join(build, "python"))
    me = [sys.executable, os.path.abspath(__file__), "--until", str(args.until), "--threads", str(args.threads)]
    sides = {"C++ API": [], "Python (numpy)": [], "L-Py": []}
    lpy = True
    for _ in range(args.repetitions):  # alternating, so a change of load falls on both
        sides["C++ API"] += run_side([baseline, KOCH, str(args.until), "1", str(args.threads)])
        sides["Python (numpy)"] += run_side(me + ["--side", "python"], env)
        if lpy:
            found = run_side(me + ["--side", "lpy"], env)
            lpy = bool(found)
            sides["L-Py"] += found

    try:
        load = os.getloadavg()[0]
    except OSError:
        load = float("nan")
    print(f"Koch's curve to t = {args.until:g}, {args.repetitions} repetitions a side, {args.threads} thread(s), "
          f"load average {load:.2f}")
    print("processor seconds (user + system) of each phase:")
    print(f"{'':16} {'cells':>10} {'grow median':>12} {'grow min':>9} {'read median':>12} {'read min':>9} "
          f"{'total median':>13}")
    totals = {}
    for name, runs in sides.items():
        if not runs:
            continue
        cells = {r["cells"] for r in runs}
        grow = [r["grow"] for r in runs]
        read = [r["read"] for r in runs]
        total = [g + r for g, r in zip(grow, read)]
        totals[name] = statistics.median(total)
        print(f"{name:16} {'/'.join(map(str, sorted(cells))):>10} {statistics.median(grow):12.3f} {min(grow):9.3f} "
              f"{statistics.median(read):12.3f} {min(read):9.3f} {totals[name]:13.3f}")
    print(f"Python / C++ (median totals): {totals['Python (numpy)'] / totals['C++ API']:.3f}")
    if "L-Py" in totals:
        print(f"L-Py / Python (median totals): {totals['L-Py'] / totals['Python (numpy)']:.3f}")
    else:
        print("L-Py: openalea.lpy is not installed here (it is not packaged by Debian); no comparison.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
