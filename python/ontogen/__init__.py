"""ontogen in Python: compile cell-language programs, grow them, read their words as
numpy arrays, draw them and run them as ``ontogen run`` does (docs/PYTHON.md)."""

import os as _os

from . import _ontogen
from . import display as _display
from ._ontogen import Cell, Program, Scene, World

__version__ = _ontogen.__version__

__all__ = [
    "Animation", "Cell", "CompileError", "Diagnostic", "ModelError", "Program", "Scene", "World",
    "compile", "load", "run", "statics", "sweep", "__version__",
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


class Animation:
    """A world grown over an interval and drawn at frames spread over it
    (``World.animation``): ``glb`` is the .glb ``ontogen run --format glb`` writes of those
    frames, ``times`` the frames' times in seconds. In a notebook it shows itself in 3-D
    with a time slider."""

    __slots__ = ("glb", "times")

    def __init__(self, glb, times):
        self.glb, self.times = glb, [float(t) for t in times]

    def save(self, path):
        """Writes the .glb to ``path``."""
        with open(path, "wb") as f:
            f.write(self.glb)

    def _repr_html_(self):
        return _display.repr_html(self.glb, self.times)

    def __repr__(self):
        return f"<ontogen.Animation {len(self.times)} frames, {self.times[0]:g} to {self.times[-1]:g} s>"


def _world_animation(self, until, frames, sets=None):
    """Grows the world on to ``until`` seconds, drawing ``frames`` frames spread evenly over
    [its time now, until] (one frame: the end) as ``ontogen run --frames`` spreads them, with
    ``sets`` (default: the program's #interpret sets that draw, else geometry). Returns an
    Animation; Ctrl-C stops it between steps."""
    glb, times = self._animation(until, int(frames), list(sets) if sets is not None else self._shown_sets)
    return Animation(glb, times)


def _world_html(self):
    """The world at its time in 3-D (a notebook's display), drawn by its #interpret sets."""
    if _display.viewer_script() is None:
        return None
    return self.scene(sets=self._shown_sets)._repr_html_()


def _scene_html(self):
    """The scene in 3-D (a notebook's display)."""
    return _display.repr_html(self.glb(), (self.time,))


World.animation = _world_animation
World._repr_html_ = _world_html
Scene._repr_html_ = _scene_html


def _define_values(name, spec):
    """A swept define's values as `ontogen sweep --define` reads them: "A:B:N" (N values
    from A to B, each (A (N-1-i) + B i) / (N-1)), "v1,v2,...", or numbers."""
    if isinstance(spec, str):
        if ":" in spec:
            parts = spec.split(":")
            if len(parts) != 3:
                raise ValueError(f"sweep: define {name}: '{spec}' is not A:B:N")
            a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
            if n < 1 or (n == 1 and a != b):
                raise ValueError(f"sweep: define {name}: N must be at least 1, and A = B when it is 1")
            return [a] if n == 1 else [(a * (n - 1 - i) + b * i) / (n - 1) for i in range(n)]
        return [float(v) for v in spec.split(",")]
    if isinstance(spec, (int, float)):
        return [float(spec)]
    return [float(v) for v in spec]


def sweep(program, out, defines=None, seeds=None, seed=None, measures=(), until=None, frames=None, step=None,
          interpret=None, workers=0, size=(128, 128), view=None, resume=False, max_cells=None, max_memory=None,
          max_events=None, max_steps=None, as_frame=False):
    """Runs a program once for every combination of ``defines`` values and seeds, as
    ``ontogen sweep`` does, writing its folder ``out`` (results.csv, results.json,
    gallery.png, thumbnails/, programs/, journal.jsonl); returns the table, a dict per row
    (``variant``, each define, ``seed``, each measure, ``error``), or with ``as_frame`` a
    pandas DataFrame. ``defines``: {name: "A:B:N" or "v1,v2" or numbers}; ``seeds``:
    (first, last) or "S1:S2" (default: ``seed``, else the program's #seed);
    ``measures``: {name: expression} or ["NAME=EXPR"]; ``max_memory`` in MiB. Ctrl-C starts
    no further variant and writes the table of what finished (``resume=True`` goes on)."""
    if as_frame:
        import pandas  # noqa: F401  (fails here, before the sweep, where pandas is missing)
    path = _os.fspath(program) if not isinstance(program, Program) else program.name
    program = _program_of(program, None)
    arguments = _ontogen._SweepArguments()
    arguments.path = path
    arguments.out = _os.fspath(out)
    arguments.defines = [(name, _define_values(name, spec)) for name, spec in (defines or {}).items()]
    if seeds is not None and seed is not None:
        raise ValueError("sweep: seed and seeds: a sweep takes one of them")
    if isinstance(seeds, str):
        first, _, last = seeds.partition(":")
        seeds = (int(first), int(last or first))
    elif isinstance(seeds, int):
        seeds = (seeds, seeds)
    elif seeds is None:
        one = program.seed if seed is None else int(seed)
        seeds = (one, one)
    arguments.seeds = (int(seeds[0]), int(seeds[1]))
    if isinstance(measures, dict):
        measures = [f"{name}={expression}" for name, expression in measures.items()]
    arguments.measures = list(measures)
    arguments.until, arguments.frames, arguments.step = until, frames, step
    arguments.sets = [interpret] if isinstance(interpret, str) else list(interpret or ())
    arguments.workers = int(workers)
    if isinstance(size, str):
        width, _, height = size.partition("x")
        size = (int(width), int(height))
    arguments.width, arguments.height = int(size[0]), int(size[1])
    arguments.view = [float(v) for v in view] if view is not None else []
    arguments.resume = bool(resume)
    for name, value in (("max_cells", max_cells), ("max_events", max_events), ("max_steps", max_steps)):
        if value is not None:
            setattr(arguments, name, int(value))
    if max_memory is not None:
        arguments.max_memory = int(max_memory) << 20
    status, message, columns, rows, _, _ = _ontogen._sweep(program, arguments)
    if status == "refused":
        raise ValueError(f"sweep: {message}")
    if status == "output error":
        raise OSError(f"sweep: {message}")
    table = []
    for variant, values, error in rows:
        row = {"variant": variant}
        for column, value in zip(columns, values):
            row[column] = (int(value) if column == "seed" else float(value)) if value != "" else None
        row["error"] = error or None
        table.append(row)
    if as_frame:
        import pandas
        return pandas.DataFrame(table, columns=["variant", *columns, "error"])
    return table
