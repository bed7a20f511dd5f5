// ontogen.run and ontogen.statics: a whole run as `ontogen run` makes it (interpreters/
// run.h), its report as data; the physics set's solve as `ontogen statics --json` gives it.

#include <pybind11/stl.h>

#include "interpreters/interpret.h"
#include "interpreters/physics/physics_set.h"
#include "interpreters/physics/statics_output.h"
#include "interpreters/run.h"
#include "interpreters/set_registry.h"
#include "python/bindings.h"
#include "python/handles.h"

namespace py = pybind11;

namespace ontogen::python {

namespace {

const char* statusName(RunStatus status) {
  switch (status) {
    case RunStatus::Ok: return "ok";
    case RunStatus::BadDefinition: return "bad definition";
    case RunStatus::ModelFailed: return "model failed";
    case RunStatus::OutputFailed: return "output failed";
    case RunStatus::Interrupted: return "interrupted";
  }
  return "model failed";
}

py::dict diagnosticDict(const RunDiagnostic& diagnostic) {
  py::dict d;
  d["severity"] = severityName(diagnostic.severity);
  d["message"] = diagnostic.message;
  d["file"] = diagnostic.span.valid() ? py::object(py::str(diagnostic.span.file->name())) : py::none();
  d["line"] = diagnostic.span.line();
  d["column"] = diagnostic.span.column();
  d["cell"] = diagnostic.cell.empty() ? py::object(py::none()) : py::object(py::str(diagnostic.cell));
  d["time"] = diagnostic.time ? py::object(py::float_(*diagnostic.time)) : py::none();
  d["count"] = diagnostic.count;
  d["text"] = formatRunDiagnostic(diagnostic);
  return d;
}

// The report: status, files, diagnostics, stats (what `ontogen run --stats` prints).
py::dict runProgram(const std::shared_ptr<ProgramHandle>& program, const std::string& out, const std::string& formats,
                    std::optional<double> until, std::optional<int> frames, uint64_t seed,
                    std::optional<std::vector<std::string>> interpret) {
  RunDef def;
  def.program = program->program;
  def.stem = program->stem;
  def.world.seed = seed;
  def.world.environment = queryEnvironmentOf(*program->program);
  def.until = until;
  def.frames = frames;
  def.out = out;
  const bool growOnly = formats.empty() || formats == "none";
  if (growOnly)
    def.sets.clear();
  else if (interpret)
    def.sets = *interpret;
  else if (!program->program->interpretSets.empty())
    def.sets = program->program->interpretSets;
  else
    def.sets = {"geometry"};
  if (!growOnly) def.setOptions.formats = formats;
  RunReport report;
  bool interrupted = false;
  withoutGil([&](const std::function<void()>& checkInterrupt) {
    def.progress = [&](int, int) {
      try {
        checkInterrupt();
      } catch (const Interrupted&) {
        interrupted = true;
        throw RunInterrupted("stopped by Ctrl-C");
      }
    };
    Run run(std::move(def));
    report = run.execute();
  });
  if (interrupted) throw py::error_already_set();  // the KeyboardInterrupt, pending
  py::dict result;
  result["status"] = statusName(report.status);
  py::list files, diagnostics;
  for (const auto& file : report.files) files.append(file.string());
  for (const RunDiagnostic& diagnostic : report.diagnostics) diagnostics.append(diagnosticDict(diagnostic));
  result["files"] = files;
  result["diagnostics"] = diagnostics;
  py::dict stats;
  stats["time"] = report.time;
  stats["cells"] = report.cells;
  stats["steps"] = report.stats.steps;
  stats["events"] = report.stats.events;
  stats["cells_born"] = report.stats.cellsBorn;
  stats["rule_firings"] = report.stats.ruleFirings;
  stats["held"] = report.held;
  stats["files"] = report.files.size();
  stats["wall"] = report.wallSeconds;
  result["stats"] = stats;
  return result;
}

py::list vectorList(const Eigen::Vector3d& v) { return py::cast(std::vector<double>{v.x(), v.y(), v.z()}); }

// (rods as `statics --json` lists them, the set's warnings as text).
py::tuple solveStatics(const std::shared_ptr<ProgramHandle>& program, std::optional<double> at) {
  const Program& compiled = *program->program;
  std::unique_ptr<InterpretationSet> made = makeInterpretationSet("physics", compiled.rootSystem().settings);
  auto& physics = dynamic_cast<PhysicsSet&>(*made);
  WorldDef def;
  def.seed = compiled.seed;
  def.environment = queryEnvironmentOf(compiled);
  withoutGil([&](const std::function<void()>& checkInterrupt) {
    World world(program->program, def);
    growTo(world, at.value_or(compiled.until), compiled.dt, def.limits, checkInterrupt);
    physics.beginFrame(FrameTarget{".", program->stem, 0, 1, world.time()});
    interpretWord(world, physics);
  });
  py::list warnings;
  for (SetWarning& warning : physics.takeWarnings())
    warnings.append(formatRunDiagnostic(
        {Severity::Warning, std::move(warning.message), warning.span, std::move(warning.cell), warning.time, warning.count}));
  const PhysicsFrame& frame = physics.frame();
  py::list rods;
  for (const RodResult& rod : frame.rods) {
    for (const Eigen::Vector3d* v : {&rod.base, &rod.tip, &rod.restTip, &rod.force, &rod.moment})
      if (!v->allFinite()) raiseModelError("ontogen: error: the statics of rod " + std::to_string(rod.id) +
                                           " are not finite (t = " + std::to_string(frame.time) + ")");
    py::dict d;
    d["id"] = rod.id;
    d["parent"] = rod.parent == kNoParentRod ? py::object(py::int_(-1)) : py::object(py::int_(rod.parent));
    d["base"] = vectorList(rod.base);
    d["tip"] = vectorList(rod.tip);
    d["rest_tip"] = vectorList(rod.restTip);
    d["length"] = rod.length;
    d["mass"] = rod.mass;
    d["force"] = vectorList(rod.force);
    d["moment"] = vectorList(rod.moment);
    rods.append(d);
  }
  return py::make_tuple(rods, warnings, frame.time, frame.g);
}

}  // namespace

void bindRun(py::module_& module) {
  module.def("_run", &runProgram, py::arg("program"), py::arg("out"), py::arg("formats"), py::arg("until"),
             py::arg("frames"), py::arg("seed"), py::arg("interpret"));
  module.def("_statics", &solveStatics, py::arg("program"), py::arg("at"));
}

}  // namespace ontogen::python
