#pragma once
// The parts of the Python module `ontogen` (python/ontogen_module.cpp), one concept a
// file: programs and their diagnostics, worlds and their words, scenes, runs. The module
// is the library's own API; the pure-Python parts (errors, display, pandas) are in
// python/ontogen/__init__.py.

#include <pybind11/pybind11.h>

namespace ontogen::python {

/// ontogen._ontogen: compile, load, Program.
void bindProgram(pybind11::module_& module);
/// World, Cell.
void bindWorld(pybind11::module_& module);
/// Scene, World.scene, World.animation.
void bindScene(pybind11::module_& module);
/// run, statics.
void bindRun(pybind11::module_& module);
/// sweep.
void bindSweep(pybind11::module_& module);

}  // namespace ontogen::python
