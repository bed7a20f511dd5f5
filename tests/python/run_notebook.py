"""docs/fig_1_24.ipynb executed headless (jupyter nbconvert --execute, Debian's
jupyter-nbconvert and python3-ipykernel), then its outputs checked by value: each plant's
module and F counts per generation against the same L-systems rewritten here as strings,
the plot as a PNG, the 3-D views as the inlined viewer with the model's .glb.

    notebook_test.py NOTEBOOK OUTPUT_DIR
Exit 0: passed; 1: failed; 77: a checker is missing (a failure when CI=true)."""

import base64
import json
import os
import re
import shutil
import subprocess
import sys

notebook, output_dir = sys.argv[1:3]
ci = os.environ.get("CI") == "true"


def missing(what):
    print(f"notebook test: {what} is missing (bash .ci/setup --checkers installs it)", file=sys.stderr)
    sys.exit(1 if ci else 77)


if not shutil.which("jupyter-nbconvert"):
    missing("jupyter-nbconvert")
for module, package in (("ipykernel", "python3-ipykernel"), ("matplotlib", "python3-matplotlib")):
    try:
        __import__(module)
    except ImportError:
        missing(package)

failures = 0


def check(condition, message):
    global failures
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures += 1
    return condition


os.makedirs(output_dir, exist_ok=True)
executed = os.path.join(output_dir, "fig_1_24.ipynb")
done = subprocess.run(["jupyter-nbconvert", "--to", "notebook", "--execute", "--output-dir", output_dir,
                       "--ExecutePreprocessor.timeout=300", notebook], capture_output=True, text=True)
if done.returncode != 0:
    print(done.stdout + done.stderr)
    sys.exit(1)
with open(executed, encoding="utf-8") as f:
    cells = [c for c in json.load(f)["cells"] if c["cell_type"] == "code"]


def outputs():
    for cell in cells:
        for output in cell.get("outputs", []):
            yield cell, output


errors = [o for _, o in outputs() if o["output_type"] == "error"]
check(not errors, f"no cell raised ({[e.get('ename') for e in errors]})")
text = "".join("".join(o["text"]) if isinstance(o["text"], list) else o["text"]
               for _, o in outputs() if o["output_type"] == "stream" and o["name"] == "stdout")

# The plants rewritten as strings, independently of ontogen: every symbol, brackets too,
# is a module of the word.
plants = {
    "a": (5, "F", {"F": "F[+F]F[-F]F"}),
    "b": (5, "F", {"F": "F[+F]F[-F][F]"}),
    "c": (4, "F", {"F": "FF-[-F+F+F]+[+F-F-F]"}),
    "d": (7, "X", {"X": "F[+X]F[-X]+X", "F": "FF"}),
    "e": (7, "X", {"X": "F[+X][-X]FX", "F": "FF"}),
    "f": (5, "X", {"X": "F-[[X]+X]+F[+FX]-X", "F": "FF"}),
}
for name, (n, axiom, rules) in plants.items():
    word = axiom
    expected = []
    for t in range(n + 1):
        if t:
            word = "".join(rules.get(symbol, symbol) for symbol in word)
        expected.append(f"{t}: {len(word)} modules {word.count('F')} F")
    line = re.search(rf"^1\.24{name}: n = {n}, (.*)$", text, re.M)
    shown = line.group(1).split(", ") if line else []
    check(shown == expected, f"1.24{name}: the notebook's counts {shown[-1:] or 'missing'} are the rewriting's "
                             f"{expected[-1]} at every generation")

pictures = [o for _, o in outputs() if "image/png" in o.get("data", {})]
check(len(pictures) == 1 and base64.b64decode(pictures[0]["data"]["image/png"])[:8] == b"\x89PNG\r\n\x1a\n",
      f"the plot is a PNG ({len(pictures)} picture(s))")

views = [o["data"]["text/html"] for _, o in outputs() if "text/html" in o.get("data", {})]
views = ["".join(v) if isinstance(v, list) else v for v in views]
check(len(views) == 2 and all(v.startswith("<iframe srcdoc=") for v in views),
      f"the world and the animation show themselves as the 3-D view ({len(views)} HTML outputs)")
viewer_path = os.environ.get("ONTOGEN_VIEWER")
if viewer_path and views:
    import html
    with open(viewer_path, encoding="utf-8") as f:
        viewer = f.read()
    for kind, view in zip(("world", "animation"), views):
        page = html.unescape(view[len('<iframe srcdoc="'):view.index('" style=')])
        model = re.search(r'<script type="application/octet-stream" id="ontogen-model">([^<]*)</script>', page)
        glb = base64.b64decode(model.group(1)) if model else b""
        check(viewer in page and glb[:4] == b"glTF",
              f"the {kind}'s view inlines the viewer ({len(viewer)} bytes) and a .glb ({len(glb)} bytes)")
times = re.search(r"^frames at \[(.*)\]$", text, re.M)
check(times is not None and [float(t) for t in times.group(1).split(", ")] == [float(t) for t in range(8)],
      f"the animation's frames are at 0, 1, ..., 7 s ({times.group(1) if times else 'missing'})")
sys.exit(1 if failures else 0)
