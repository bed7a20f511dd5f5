// ontogen.compile, ontogen.load and Program: a program text (or a cpfg or L-Py file,
// converted) compiled against every interpretation set, as `ontogen check` does. A text
// with errors gives no program but its diagnostics, which ontogen/__init__.py raises as
// ontogen.CompileError.

#include <filesystem>

#include <pybind11/stl.h>

#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "lang/convert/convert.h"
#include "lang/program_file.h"
#include "model/diagnostics.h"
#include "python/bindings.h"
#include "python/handles.h"

namespace py = pybind11;

namespace ontogen::python {

namespace {

// (file, line, column, message, severity): file None and line 0 for what belongs to no text.
py::tuple diagnosticTuple(const Diagnostic& diagnostic) {
  py::object file = diagnostic.span.valid() ? py::object(py::str(diagnostic.span.file->name())) : py::none();
  return py::make_tuple(file, diagnostic.span.line(), diagnostic.span.column(), diagnostic.message,
                        severityName(diagnostic.severity));
}

py::list diagnosticList(const DiagnosticSink& sink) {
  py::list list;
  for (const Diagnostic& diagnostic : sink.diagnostics()) list.append(diagnosticTuple(diagnostic));
  return list;
}

std::vector<DefineOverride> definesOf(const py::object& defines) {
  std::vector<DefineOverride> list;
  if (defines.is_none()) return list;
  for (auto [name, value] : py::cast<py::dict>(defines))
    list.push_back({py::cast<std::string>(name), py::cast<double>(value)});
  return list;
}

// (program or None, diagnostics, their text with carets).
py::tuple compileText(std::string name, std::string text, const py::object& defines) {
  CompileOptions options;
  options.commandSets = commandSets();
  options.defines = definesOf(defines);
  DiagnosticSink sink;
  std::unique_ptr<Program> program;
  {
    py::gil_scoped_release release;
    program = compileSource(name, text, sink, options);
  }
  py::object result = py::none();
  if (program) {
    auto handle = std::make_shared<ProgramHandle>();
    handle->program = std::move(program);
    handle->name = name;
    handle->stem = std::filesystem::path(name).stem().string();
    if (handle->stem.empty() || handle->stem[0] == '<') handle->stem = "model";
    handle->text = std::move(text);
    result = py::cast(handle);
  }
  return py::make_tuple(result, diagnosticList(sink), formatDiagnostics(sink));
}

// A file's text, converted when it is cpfg's (.l, with its view file and the function
// files that names) or L-Py's (.lpy), read as the command line reads it
// (lang/program_file.h: regular files, the source limit): (name, text) or, when
// conversion fails, (None, diagnostics, their text). Raises OSError when it cannot be read.
py::tuple readProgram(const std::string& path) {
  DiagnosticSink sink;
  ProgramFileText read;
  {
    py::gil_scoped_release release;
    read = readProgramFile(path, ProgramFileDef{}, sink);
  }
  if (read.failure == ProgramFileFailure::Unreadable || (!read.text && !read.original)) {
    PyErr_SetString(PyExc_OSError, read.error.c_str());
    throw py::error_already_set();
  }
  if (!read.text) {
    // The diagnostics point into read.original, alive until they are written out here.
    std::string text = formatDiagnostics(sink);
    text += "ontogen: " + path + " cannot be converted from " +
            std::string(convert::dialectName(*convert::dialectOfPath(path))) + "\n";
    return py::make_tuple(py::none(), diagnosticList(sink), text);
  }
  return py::make_tuple(read.name, *read.text);
}

py::dict definesDict(const ProgramHandle& handle) {
  py::dict defines;
  // A name defined in several blocks: the first (the top level's) is what it names.
  for (const ProgramDefine& define : handle.program->defines)
    if (!defines.contains(define.name)) defines[py::str(define.name)] = define.value;
  return defines;
}

}  // namespace

void bindProgram(py::module_& module) {
  py::class_<ProgramHandle, std::shared_ptr<ProgramHandle>>(module, "Program",
                                                            "A compiled program (ontogen.compile, ontogen.load).")
      .def_property_readonly("defines", &definesDict, "Every #define with its value, name -> value.")
      .def_property_readonly("name", [](const ProgramHandle& p) { return p.name; },
                             "The name diagnostics show (the path, or the name given to compile).")
      .def_property_readonly("source", [](const ProgramHandle& p) { return p.text; },
                             "The cell-language text it was compiled from (a converted file's conversion).")
      .def_property_readonly("seed", [](const ProgramHandle& p) { return p.program->seed; }, "#seed, else 1.")
      .def_property_readonly("until", [](const ProgramHandle& p) { return p.program->until; }, "#until, seconds.")
      .def_property_readonly("dt", [](const ProgramHandle& p) { return p.program->dt; }, "#dt, seconds.")
      .def_property_readonly("interpret", [](const ProgramHandle& p) { return p.program->interpretSets; },
                             "The sets of #interpret (empty: geometry).")
      .def("world", &makeWorld, py::arg("seed") = 0, py::arg("threads") = 0,
           "A new world growing the program at time 0, with `seed` (0 is a seed like any other) on "
           "`threads` threads (0: all cores; the word does not depend on them).")
      .def("__repr__", [](const ProgramHandle& p) { return "<ontogen.Program " + p.name + ">"; });
  module.def("_compile", &compileText, py::arg("name"), py::arg("text"), py::arg("defines") = py::none());
  module.def("_read", &readProgram, py::arg("path"));
}

}  // namespace ontogen::python
