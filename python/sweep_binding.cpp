// ontogen.sweep: a program run once for every combination of values of some #defines and
// of seeds into one table, as `ontogen sweep` runs it (batch/sweep.h), on this machine;
// the table comes back as data (python/ontogen/__init__.py makes the rows dicts).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/stl.h>

#include "batch/sweep.h"
#include "python/bindings.h"
#include "python/handles.h"

namespace py = pybind11;

namespace ontogen::python {

namespace {

struct SweepArguments {
  std::string path;
  std::string out;
  std::vector<std::pair<std::string, std::vector<double>>> defines;
  std::pair<uint64_t, uint64_t> seeds;
  std::vector<std::string> measures;
  std::optional<double> until, step;
  std::optional<int> frames;
  std::vector<std::string> sets;
  unsigned workers = 0;
  int width = 128, height = 128;
  std::vector<double> view;
  bool resume = false;
  WorldLimits limits;
};

// (status, message, columns, rows as (variant, values, error), variants, failed).
py::tuple sweep(const std::shared_ptr<ProgramHandle>& program, const SweepArguments& arguments) {
  SweepDef def;
  SweepSettings& settings = def.settings;
  settings.path = arguments.path;
  settings.stem = program->stem;
  settings.text = program->text;
  settings.program = program->program;
  settings.measures = arguments.measures;
  settings.sets = arguments.sets;
  settings.limits = arguments.limits;
  settings.until = arguments.until;
  settings.step = arguments.step;
  settings.frames = arguments.frames;
  settings.width = arguments.width;
  settings.height = arguments.height;
  settings.view = arguments.view;
  settings.workers = arguments.workers;
  for (const auto& [name, values] : arguments.defines) def.defines.push_back(SweptDefine{name, values, {}});
  def.seeds = arguments.seeds;
  def.out = arguments.out;
  def.resume = arguments.resume;
  def.sizeText = std::to_string(arguments.width) + "x" + std::to_string(arguments.height);
  SweepResult result;
  withoutGil([&](const std::function<void()>& checkInterrupt) {
    bool interrupted = false;
    // Ctrl-C starts no further variant; the running ones finish and the table of what
    // finished is written (resume=True goes on), then the KeyboardInterrupt is raised.
    def.stop = [&] {
      if (!interrupted) {
        try {
          checkInterrupt();
        } catch (const Interrupted&) {
          interrupted = true;
        }
      }
      return interrupted;
    };
    result = runSweep(std::move(def));
    if (interrupted) throw Interrupted{};
  });
  const char* status = "done";
  switch (result.batch.status) {
    case BatchStatus::Done: status = "done"; break;
    case BatchStatus::Refused: status = "refused"; break;
    case BatchStatus::OutputError: status = "output error"; break;
    case BatchStatus::Stopped: status = "stopped"; break;
  }
  py::list rows;
  for (const SweepRow& row : result.batch.table.rows) rows.append(py::make_tuple(row.variant, row.values, row.error));
  return py::make_tuple(status, result.batch.message, result.batch.table.columns, rows, result.count,
                        result.batch.failed);
}

}  // namespace

void bindSweep(py::module_& module) {
  py::class_<SweepArguments>(module, "_SweepArguments")
      .def(py::init<>())
      .def_readwrite("path", &SweepArguments::path)
      .def_readwrite("out", &SweepArguments::out)
      .def_readwrite("defines", &SweepArguments::defines)
      .def_readwrite("seeds", &SweepArguments::seeds)
      .def_readwrite("measures", &SweepArguments::measures)
      .def_readwrite("until", &SweepArguments::until)
      .def_readwrite("step", &SweepArguments::step)
      .def_readwrite("frames", &SweepArguments::frames)
      .def_readwrite("sets", &SweepArguments::sets)
      .def_readwrite("workers", &SweepArguments::workers)
      .def_readwrite("width", &SweepArguments::width)
      .def_readwrite("height", &SweepArguments::height)
      .def_readwrite("view", &SweepArguments::view)
      .def_readwrite("resume", &SweepArguments::resume)
      .def_property(
          "max_cells", [](const SweepArguments& a) { return a.limits.maxCells; },
          [](SweepArguments& a, uint64_t v) { a.limits.maxCells = v; })
      .def_property(
          "max_events", [](const SweepArguments& a) { return a.limits.maxEventsPerStep; },
          [](SweepArguments& a, uint64_t v) { a.limits.maxEventsPerStep = v; })
      .def_property(
          "max_steps", [](const SweepArguments& a) { return a.limits.maxSteps; },
          [](SweepArguments& a, uint64_t v) { a.limits.maxSteps = v; })
      .def_property(
          "max_memory", [](const SweepArguments& a) { return a.limits.maxMemoryBytes; },
          [](SweepArguments& a, uint64_t v) { a.limits.maxMemoryBytes = v; });
  module.def("_sweep", &sweep, py::arg("program"), py::arg("arguments"));
}

}  // namespace ontogen::python
