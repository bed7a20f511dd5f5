#!/usr/bin/env python3
"""Converts and checks every real cpfg (.l) and L-Py (.lpy) file of two folders and
prints how many convert and check clean, with the most frequent first errors.

Run by hand (not part of the test command), against files fetched outside the
repository:

  python3 tests/convert/sweep_real_files.py --ontogen build/apps/ontogen \
      --lpy /path/to/lpy --vlab /path/to/vlab [--list]

The L-Py set is every .lpy under lpy/share and lpy/test (its examples and tests); the
cpfg set every .l under vlab/oofs/ext/11-CPFG and vlab/oofs/ext/10-manuals that holds an
`Lsystem:` line and is no panel or lpfg (C++) file. A file is clean when `ontogen
convert` and `ontogen check` both exit 0. Any other exit than 0, 1 and 6 (a crash, a
hang, an internal error) is listed as a failure of ontogen itself.
"""
import argparse
import collections
import pathlib
import re
import subprocess
import sys


def lpy_files(root):
    root = pathlib.Path(root)
    return sorted(p for d in ("share", "test") for p in (root / d).rglob("*.lpy"))


def cpfg_files(root):
    root = pathlib.Path(root) / "oofs" / "ext"
    found = []
    for d in ("11-CPFG", "10-manuals"):
        for p in (root / d).rglob("*.l"):
            text = p.read_text(errors="replace")
            if p.name == "panel.l" or "lpfgall" in text:
                continue
            if re.search(r"^\s*lsystem:", text, re.I | re.M):
                found.append(p)
    return sorted(found)


def run(ontogen, command, path):
    try:
        done = subprocess.run([ontogen, command, str(path)], capture_output=True, timeout=60)
    except subprocess.TimeoutExpired:
        return None, "hang"
    err = done.stderr.decode(errors="replace")
    # The first error, else the first warning: a warning is no reason for a failure.
    lines = err.splitlines()
    first = next((l for l in lines if ": error: " in l), None) or next(
        (l for l in lines if ": warning: " in l), err.strip()[:200])
    return done.returncode, first


def reason(line):
    # The message without its place, and quoted names made generic, for counting.
    message = line.split(": error: ", 1)[-1].split(": warning: ", 1)[-1]
    return re.sub(r"'[^']*'", "'…'", message)[:110]


def sweep(ontogen, files, label, show):
    clean = 0
    faults = []
    reasons = collections.Counter()
    for path in files:
        code, first = run(ontogen, "convert", path)
        if code == 0:
            code, first = run(ontogen, "check", path)
        if code == 0:
            clean += 1
        elif code not in (1, 6):
            faults.append((path, code, first))
        else:
            reasons[reason(first)] += 1
        if show:
            print(f"{'ok  ' if code == 0 else f'{code!s:4}'} {path}  {'' if code == 0 else first}")
    print(f"{label}: {clean} of {len(files)} convert and check clean")
    for text, count in reasons.most_common(12):
        print(f"  {count:4}  {text}")
    for path, code, first in faults:
        print(f"  FAULT exit {code}: {path}: {first}")
    return not faults


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ontogen", default="build/apps/ontogen")
    parser.add_argument("--lpy", required=True, help="a checkout of openalea/lpy")
    parser.add_argument("--vlab", required=True, help="a checkout of AlgorithmicBotany/vlab")
    parser.add_argument("--list", action="store_true", help="print every file's outcome")
    args = parser.parse_args()
    ok = sweep(args.ontogen, lpy_files(args.lpy), "L-Py (.lpy)", args.list)
    ok = sweep(args.ontogen, cpfg_files(args.vlab), "cpfg (.l)", args.list) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
