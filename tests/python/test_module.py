"""The Python module against the ontogen executable: words, arrays, scenes, runs, errors
and threads (docs/PYTHON.md)."""

import math
import os
import pathlib
import re
import shutil
import subprocess
import threading

import numpy as np
import pytest

import ontogen
from conftest import MODELS, SOURCE, cli, word_json

KOCH = MODELS / "koch.cell"


def test_version_is_the_projects():
    project = re.search(r"project\(ontogen VERSION ([0-9.]+)", (SOURCE / "CMakeLists.txt").read_text()).group(1)
    assert ontogen.__version__ == project


def test_koch_word_at_three():
    program = ontogen.load(KOCH)
    world = program.world(seed=program.seed)
    world.advance(3)
    assert world.time == 3
    word = world.word()
    assert len(word) == 249
    assert sum(cell.label == "F" for cell in word) == 125
    ids = [cell.id for cell in word]
    assert len(set(ids)) == 249
    expected = word_json(KOCH, [3], program.seed)["times"][0]["cells"]
    assert [cell.label for cell in word] == [c["label"] for c in expected]
    assert ids == [c["id"] for c in expected]
    assert [cell.parent for cell in word] == [c["parent"] for c in expected]
    assert word[0].parent == -1 and word[0].pool is None and word[0].params == ()


def flatten(cells, out):
    """JSON cells in pool order, a system cell followed by its pool's, as World.arrays has them."""
    for cell in cells:
        out.append(cell)
        flatten(cell.get("pool", []), out)
    return out


def number(value):
    return math.nan if value is None else value


def check_arrays(arrays, cells, where):
    n = len(cells)
    assert arrays["id"].dtype == np.uint64 and arrays["id"].shape == (n,), where
    assert arrays["parent"].dtype == np.int64 and arrays["age"].dtype == np.float64, where
    assert arrays["id"].tolist() == [c["id"] for c in cells], where
    assert arrays["parent"].tolist() == [c["parent"] for c in cells], where
    assert [arrays["labels"][i] for i in arrays["label"]] == [c["label"] for c in cells], where
    assert np.array_equal(arrays["age"], np.array([number(c["age"]) for c in cells], dtype=float), equal_nan=True), where
    k = max((len(c["params"]) for c in cells), default=0)
    params = np.full((n, k), np.nan)
    for i, c in enumerate(cells):
        params[i, : len(c["params"])] = [number(v) for v in c["params"]]
    assert arrays["params"].shape == (n, k), where
    assert np.array_equal(arrays["params"], params, equal_nan=True), where
    if any("position" in c for c in cells):
        positions = np.full((n, 3), np.nan)
        for i, c in enumerate(cells):
            p = c.get("position", [])
            positions[i, : len(p)] = [number(v) for v in p]
        assert np.array_equal(arrays["position"], positions, equal_nan=True), where
    else:
        assert "position" not in arrays, where


@pytest.mark.parametrize("model", sorted(p.name for p in MODELS.glob("*.cell")))
def test_arrays_equal_the_json_word(model):
    program = ontogen.load(MODELS / model)
    # The times the engine's model test grows every model to, and half of it.
    until = min(program.until, max(8 * program.dt, 4.0))
    times = [until / 2, until]
    document = word_json(MODELS / model, times, program.seed)
    world = program.world(seed=program.seed)
    for t, expected in zip(times, document["times"]):
        world.advance(t)
        check_arrays(world.arrays(), flatten(expected["cells"], []), f"{model} at t = {t}")


def test_a_located_compile_error():
    text = "lsystem bad {\n  axiom A(1)\n  A(x) -> A(x + nothing)\n}\n"
    with pytest.raises(ontogen.CompileError) as raised:
        ontogen.compile(text, name="bad.cell")
    error = raised.value
    first = error.diagnostics[0]
    assert (first.file, first.line, first.severity) == ("bad.cell", 3, "error")
    assert first.column > 0 and first.message
    lines = str(error).splitlines()
    assert lines[0].startswith(f"bad.cell:3:{first.column}: error: ")
    assert lines[1] == "  A(x) -> A(x + nothing)"
    assert first.column == lines[1].index("nothing") + 1
    assert lines[2].index("^") == first.column - 1


def test_an_unknown_define_is_a_compile_error_of_no_place():
    with pytest.raises(ontogen.CompileError) as raised:
        ontogen.load(KOCH, defines={"nothing": 1})
    assert raised.value.diagnostics[0].file is None
    assert "nothing" in raised.value.diagnostics[0].message


def test_defines_and_program_defines():
    text = "#define LEN 2\nlsystem a {\n  axiom F(LEN)\n}\n"
    assert ontogen.compile(text).defines == {"LEN": 2}
    program = ontogen.compile(text, defines={"LEN": 5})
    assert program.defines == {"LEN": 5}
    assert program.world().word()[0].params == (5.0,)


def test_a_limit_is_a_model_error():
    program = ontogen.load(KOCH)
    world = program.world()
    with pytest.raises(ontogen.ModelError, match="step"):
        world.advance(1e12)  # more steps than the limit allows


def test_two_threads_grow_what_each_grows_alone():
    program = ontogen.load(MODELS / "stochastic_tree.cell")
    t = min(program.until, 8.0)

    def grown(seed):
        world = program.world(seed=seed, threads=1)
        world.advance(t)
        return world.arrays()

    alone = [grown(seed) for seed in (1, 2)]
    together = [None, None]
    threads = [threading.Thread(target=lambda i=i: together.__setitem__(i, grown(i + 1))) for i in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for a, b in zip(alone, together):
        assert a["id"].tolist() == b["id"].tolist()
        assert np.array_equal(a["params"], b["params"], equal_nan=True)
        assert np.array_equal(a["age"], b["age"])
    assert alone[0]["id"].tolist() != alone[1]["id"].tolist()


def read_obj(path):
    vertices, faces, lines = [], [], []
    for line in pathlib.Path(path).read_text().splitlines():
        tag, *rest = line.split()  or [""]
        if tag == "v":
            vertices.append([float(x) for x in rest])
        elif tag == "f":
            faces.append([int(c.split("/")[0]) - 1 for c in rest])
        elif tag == "l":
            lines.append([int(c) - 1 for c in rest])
    return np.array(vertices), np.array(faces, dtype=np.uint32).reshape(-1, 3), np.array(lines, dtype=np.uint32).reshape(-1, 2)


@pytest.mark.parametrize("model,until", [("koch.cell", 3), ("branching.cell", None)])
def test_scene_is_the_obj_that_run_writes(model, until, tmp_path):
    program = ontogen.load(MODELS / model)
    until = until if until is not None else program.until
    cli("run", MODELS / model, "--format", "obj", "--frames", "1", "--until", until, "--seed", program.seed,
        "--out", tmp_path)
    vertices, faces, lines = read_obj(tmp_path / (pathlib.Path(model).stem + ".obj"))
    world = program.world(seed=program.seed)
    world.advance(until)
    scene = world.scene()
    assert scene.vertices.dtype == np.float32 and scene.indices.dtype == np.uint32
    assert scene.vertices.shape == vertices.shape
    assert scene.normals.shape == vertices.shape and scene.colors.shape == (len(vertices), 4)
    assert np.allclose(scene.vertices, vertices, rtol=1e-6, atol=1e-6 * np.abs(vertices).max())
    assert np.array_equal(scene.indices, faces)
    assert np.array_equal(scene.lines, lines)
    assert len(scene.nodes) > 0 and scene.nodes["transform"].shape[1:] == (4, 4)
    ids = {cell.id for cell in world.word()}
    assert set(scene.nodes["id"].tolist()) <= ids


def test_run_writes_a_glb_the_validator_accepts(tmp_path):
    modules = SOURCE / ".tools" / "node_modules"
    if not (modules / "gltf-validator" / "package.json").exists() or shutil.which("node") is None:
        if os.environ.get("CI") == "true":
            pytest.fail("the Khronos glTF validator is missing (bash .ci/setup installs it)")
        pytest.skip("the Khronos glTF validator is missing")
    report = ontogen.run(MODELS / "branching.cell", tmp_path, formats=("glb",), frames=3)
    assert report["status"] == "ok", report["diagnostics"]
    glb = [f for f in report["files"] if f.endswith(".glb")]
    assert glb == [str(tmp_path / "branching.glb")]
    assert report["stats"]["cells"] > 0 and report["stats"]["files"] == 1
    checked = subprocess.run(["node", SOURCE / "tests" / "interpreters" / "validate_gltf.js", modules, glb[0]],
                             capture_output=True, text=True)
    assert checked.returncode == 0, checked.stdout + checked.stderr


def test_run_reports_what_failed(tmp_path):
    failed = ontogen.run(KOCH, tmp_path, formats=("obj",), until=1e12)  # more steps than the limit
    assert failed["status"] == "model failed" and failed["files"] == []
    assert failed["diagnostics"][0]["severity"] == "error" and "step" in failed["diagnostics"][0]["message"]
    bad = ontogen.run(KOCH, tmp_path, formats=("nothing",))
    assert bad["status"] == "bad definition" and "nothing" in bad["diagnostics"][0]["message"]


def test_the_example_of_docs_python_runs(monkeypatch):
    """docs/PYTHON.md's example (ABOP Fig. 1.24) as a notebook would run it, headless."""
    try:
        import matplotlib
    except ImportError:
        if os.environ.get("CI") == "true":
            pytest.fail("matplotlib is missing (bash .ci/setup --checkers installs python3-matplotlib)")
        pytest.skip("matplotlib is missing")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    monkeypatch.setattr(plt, "show", lambda *args, **kwargs: None)
    text = (SOURCE / "docs" / "PYTHON.md").read_text()
    example = text[text.index("## An example"):]
    code = example[example.index("```python\n") + len("```python\n"):example.index("\n```", example.index("```python"))]
    scope = {}
    exec(compile(code, "docs/PYTHON.md", "exec"), scope)
    # The last plant counted, (f), starts from X alone; every segment of (d) is a line.
    assert scope["counts"][0] == 0 and scope["counts"][-1] > 0
    assert len(scope["ends"]) == len(scope["scene"].lines) > 0
    plt.close("all")
