"""ontogen in Python: compile cell-language programs, grow them, read their words as
numpy arrays, draw them and run them as ``ontogen run`` does (docs/PYTHON.md)."""

import os as _os

from . import _ontogen
from ._ontogen import Cell, Program, Scene, World

__version__ = _ontogen.__version__

__all__ = [
    "Cell", "CompileError", "Diagnostic", "ModelError", "Program", "Scene", "World",
    "compile", "load", "run", "statics", "__version__",
]


class Diagnostic:
    """An error, warning or note of the compiler, located in its text (``file`` is None
    and ``line`` 0 for one that belongs to no text, such as an unknown define)."""

    __slots__ = ("file", "line", "column", "message", "severity")

    def __init__(self, file, line, column, message, severity):
        self.file, self.line, self.column = file, line, column
        self.message, self.severity = message, severity

    def __repr__(self):
        return f"<ontogen.Diagnostic {self.file}:{self.line}:{self.column}: {self.severity}: {self.message}>"


class CompileError(Exception):
    """A program with errors; ``str()`` is the compiler's text (the line, a caret under the
    place), ``diagnostics`` the list of Diagnostic."""

    def __init__(self, text, diagnostics):
        super().__init__(text)
        self.diagnostics = diagnostics

    def __str__(self):
        return self.args[0]


class ModelError(RuntimeError):
    """The model failed while it grew (a rule's error, located) or passed a growth limit."""


def _compiled(result):
    program, diagnostics, text = result
    if program is None:
        raise CompileError(text, [Diagnostic(*d) for d in diagnostics])
    return program


def compile(source, defines=None, name=None):
    """Compiles a program text; ``defines`` (name -> number) set its ``#define``s, ``name``
    is what diagnostics show (imports are read relative to its folder)."""
    return _compiled(_ontogen._compile(name if name is not None else "<string>", source, defines))


def load(path, defines=None):
    """Reads and compiles a program file: the cell language, or cpfg's ``.l`` or L-Py's
    ``.lpy`` converted as ``ontogen`` converts them."""
    read = _ontogen._read(_os.fspath(path))
    if read[0] is None:
        raise CompileError(read[2], [Diagnostic(*d) for d in read[1]])
    name, text = read
    return _compiled(_ontogen._compile(name, text, defines))


def _program_of(program_or_path, defines):
    if isinstance(program_or_path, Program):
        if defines:
            return _compiled(_ontogen._compile(program_or_path.name, program_or_path.source, defines))
        return program_or_path
    return load(program_or_path, defines)


def run(program_or_path, out, formats=("glb", "png"), until=None, frames=None, seed=0, defines=None,
        interpret=None):
    """Runs a program as ``ontogen run`` does, writing its outputs into the folder ``out``;
    returns {"status", "files", "diagnostics", "stats"}. ``formats`` () or None grows
    without interpreting; ``interpret`` names the sets (default: #interpret, else
    geometry)."""
    program = _program_of(program_or_path, defines)
    if isinstance(formats, str):
        formats = (formats,)
    return _ontogen._run(program, _os.fspath(out), ",".join(formats or ()), until, frames, seed,
                         list(interpret) if interpret is not None else None)


def statics(program, at=None):
    """The physics set's rigid statics of the word at ``at`` (default: #until), rod by rod,
    with the fields of ``ontogen statics --json``; the set's warnings as Python warnings."""
    import warnings
    rods, problems, _, _ = _ontogen._statics(_program_of(program, None), at)
    for problem in problems:
        warnings.warn(problem, RuntimeWarning, stacklevel=2)
    return rods
