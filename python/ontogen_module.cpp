// The Python module ontogen._ontogen over the library (docs/PYTHON.md): the engine grows
// with the GIL released, Ctrl-C stops a growth between steps, the engine's errors are
// ontogen.ModelError.

#include <chrono>

#include "core/limits.h"
#include "core/parents.h"
#include "core/salts.h"
#include "core/successors.h"
#include "interpreters/interpretation_set.h"
#include "python/bindings.h"
#include "python/handles.h"

namespace py = pybind11;

namespace ontogen::python {

namespace {
// Checks at most this often: taking the GIL after every step of a model of many tiny
// steps would cost more than the steps.
constexpr auto kCheckEvery = std::chrono::milliseconds(50);
}  // namespace

uint64_t shownId(uint64_t id) { return id & kIdBits; }

int64_t shownParent(uint64_t parent) {
  return parent == kNoParent ? -1 : static_cast<int64_t>(parent & kIdBits);
}

void raiseModelError(const std::string& message) {
  py::object type = py::module_::import("ontogen").attr("ModelError");
  PyErr_SetObject(type.ptr(), py::str(message).ptr());
  throw py::error_already_set();
}

void withoutGil(const std::function<void(const std::function<void()>&)>& work) {
  py::module_ threading = py::module_::import("threading");
  const bool mainThread = threading.attr("current_thread")().is(threading.attr("main_thread")());
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    auto last = std::chrono::steady_clock::now();
    const std::function<void()> check = [&] {
      if (!mainThread) return;  // Python delivers signals to its main thread alone
      const auto now = std::chrono::steady_clock::now();
      if (now - last < kCheckEvery) return;
      last = now;
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) throw Interrupted{};
    };
    try {
      work(check);
    } catch (const Interrupted&) {
      interrupted = true;
    }
  }
  if (interrupted) throw py::error_already_set();
}

}  // namespace ontogen::python

PYBIND11_MODULE(_ontogen, module) {
  using namespace ontogen;
  module.doc() = "ontogen's engine (the module ontogen wraps it)";
  module.attr("__version__") = ONTOGEN_VERSION;
  // The engine's failures as Python's: ontogen.ModelError is defined in Python
  // (ontogen/__init__.py), found when the first one is raised.
  py::register_exception_translator([](std::exception_ptr thrown) {
    auto raise = [](const std::string& message) {
      py::object type = py::module_::import("ontogen").attr("ModelError");
      PyErr_SetObject(type.ptr(), py::str(message).ptr());
    };
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const LimitError& error) {
      raise(std::string("ontogen: error: ") + error.what());
    } catch (const ModelError& error) {
      raise(error.what());
    } catch (const InstructionError& error) {
      raise(error.what());
    }
  });
  python::bindProgram(module);
  python::bindWorld(module);
  python::bindScene(module);
  python::bindRun(module);
  python::bindSweep(module);
}
