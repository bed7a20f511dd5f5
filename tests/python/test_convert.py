"""cpfg's and L-Py's files loaded from Python, read as the command line reads them: the view
file and the function files it names beside the file, regular files only (docs/PYTHON.md)."""

import os
import shutil

import pytest

import ontogen
from conftest import SOURCE

CONVERT = SOURCE / "tests" / "convert"


def words(program, times):
    world = program.world(seed=program.seed)
    grown = []
    for t in times:
        world.advance(t)
        grown.append([(cell.label, cell.params) for cell in world.word()])
    return grown


def test_a_cpfg_file_reads_the_function_its_view_file_names():
    # func(1, 0.5) of cpfg_vocabulary.func is its middle sample, 3: the words cpfg derives
    # (tests/apps/convert_cli_test.cpp states them too).
    program = ontogen.load(CONVERT / "cpfg_vocabulary.l")
    one, two = words(program, [1, 2])
    assert one == [("Texture", (2.0,)), ("SetElasticity", (1.0, 0.0)), ("A", (0.5,)), ("[", ()), ("+", ()),
                   ("B", ()), ("D", ()), ("]", ()), ("C", ()), ("F", (3.0,))]
    assert two[-3:] == [("C", ()), ("F", (3.0,)), ("F", (3.0,))]


def test_a_function_file_that_is_no_regular_file_is_refused_without_waiting(tmp_path):
    for name in ("cpfg_vocabulary.l", "cpfg_vocabulary.v"):
        shutil.copy(CONVERT / name, tmp_path / name)
    os.mkfifo(tmp_path / "cpfg_vocabulary.func")  # opened for reading, it would block
    with pytest.raises(ontogen.CompileError) as raised:
        ontogen.load(tmp_path / "cpfg_vocabulary.l")
    first = raised.value.diagnostics[0]
    assert (first.file, first.line, first.severity) == (str(tmp_path / "cpfg_vocabulary.l"), 10, "error")
    assert "the function file 'cpfg_vocabulary.func' cannot be read" in first.message


def test_the_view_file_is_the_one_the_specifications_name(tmp_path):
    (tmp_path / "plant.l").write_text("Lsystem: 1\nAxiom: F+F\nendlsystem\n")
    (tmp_path / "view.v").write_text("angle increment: 20\n")
    (tmp_path / "specifications").write_text("model:\n\tgenerate:\n\t\tcpfg -M plant.mat plant.l view.v\n")
    program = ontogen.load(tmp_path / "plant.l")
    assert "  #angle 20\n" in program.source
