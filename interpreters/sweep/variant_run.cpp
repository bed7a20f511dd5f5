#include "interpreters/sweep/variant_run.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/word.h"
#include "interpreters/creature/creature_set.h"
#include "interpreters/dynamics/dynamics_set.h"
#include "interpreters/formats/renderer.h"
#include "interpreters/geometry/geometry_set.h"
#include "interpreters/physics/physics_set.h"
#include "interpreters/set_registry.h"

namespace ontogen {

namespace {

// A foot is on the ground within this of the ground's height: the gait plants it there
// exactly, and anything above is a foot in the air.
constexpr double kOnGround = 1e-6;

class CellCounter : public WordVisitor {
 public:
  explicit CellCounter(RunQuantities& into) : into_(into) {}
  void cell(const WordCellView& cell) override {
    if (auto found = into_.labels.find(cell.label); found != into_.labels.end()) ++found->second;
  }
  // Labels alone: a word grown without ids is counted as it is held.
  bool readsIds() const override { return false; }

 private:
  RunQuantities& into_;
};

// What the frames show, gathered as the run draws them.
struct FrameWatch {
  Box bounds;
  bool drawn = false;
  double ground = 0;
  struct Foot {
    glm::dvec3 planted{0.0};
    bool down = false;
  };
  std::map<uint64_t, Foot> feet;
  double slip = 0;

  void see(const Scene& scene) {
    bounds = scene.geometry.bounds();
    drawn = true;
    for (const SceneJoint& joint : scene.skeleton.joints) {
      if (!joint.foot) continue;
      Foot& foot = feet[joint.id];
      if (std::abs(joint.position.y - ground) > kOnGround) {
        foot.down = false;
        continue;
      }
      if (!foot.down) foot = {joint.position, true};
      slip = std::max(slip, glm::length(joint.position - foot.planted));
    }
  }
};

void addSceneQuantities(const FrameWatch& watch, RunQuantities& q) {
  const bool empty = !watch.drawn || watch.bounds.empty;
  const glm::dvec3 lo = empty ? glm::dvec3(0.0) : watch.bounds.min;
  const glm::dvec3 hi = empty ? glm::dvec3(0.0) : watch.bounds.max;
  q.values["min_x"] = lo.x;
  q.values["min_y"] = lo.y;
  q.values["min_z"] = lo.z;
  q.values["max_x"] = hi.x;
  q.values["max_y"] = hi.y;
  q.values["max_z"] = hi.z;
  q.values["width"] = hi.x - lo.x;
  q.values["height"] = hi.y - lo.y;
  q.values["depth"] = hi.z - lo.z;
}

void addPhysicsQuantities(const PhysicsSet& physics, RunQuantities& q) {
  const PhysicsFrame& frame = physics.frame();
  double mass = 0, deflection = 0;
  const RodResult* root = nullptr;
  for (const RodResult& rod : frame.rods) {
    mass += rod.mass;
    deflection = std::max(deflection, (rod.tip - rod.restTip).norm());
    if (!root && rod.parent == kNoParentRod) root = &rod;
  }
  q.values["rods"] = static_cast<double>(frame.rods.size());
  q.values["mass"] = mass;
  q.values["deflection"] = deflection;
  q.values["root_force"] = root ? root->force.norm() : 0.0;
  q.values["root_moment"] = root ? root->moment.norm() : 0.0;
}

std::string compileError(const DiagnosticSink& sink) {
  for (const Diagnostic& diagnostic : sink.diagnostics())
    if (diagnostic.severity == Severity::Error)
      return oneLine(RunDiagnostic{Severity::Error, diagnostic.message, diagnostic.span, {}, {}, 1});
  return "the program has errors";
}

}  // namespace

std::string oneLine(const RunDiagnostic& diagnostic) {
  std::string text;
  if (diagnostic.span.valid())
    text = diagnostic.span.file->name() + ":" + std::to_string(diagnostic.span.line()) + ":" +
           std::to_string(diagnostic.span.column()) + ": ";
  text += diagnostic.message;
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

VariantResult runVariant(VariantDef def) {
  VariantResult result;
  result.measures.assign(def.measures.size(), std::numeric_limits<double>::quiet_NaN());
  DiagnosticSink sink;
  std::unique_ptr<Program> compiled = compileSource(def.name, def.text, sink, def.compile);
  if (!compiled) {
    result.error = compileError(sink);
    return result;
  }
  // Query modules are answered as `ontogen run` answers them (interpreters/set_registry.h).
  def.run.world.environment = queryEnvironmentOf(*compiled);
  def.run.program = std::move(compiled);
  RenderDef render = def.run.setOptions.render;
  FrameWatch watch;
  def.run.frameDrawn = [&watch](const Scene& scene) { watch.see(scene); };
  Run run(std::move(def.run));
  for (const auto& set : run.sets())
    if (const auto* creature = dynamic_cast<const CreatureSet*>(set.get())) watch.ground = creature->ground();
  const RunReport report = run.execute();
  if (!report.ok()) {
    for (const RunDiagnostic& diagnostic : report.diagnostics)
      if (diagnostic.severity == Severity::Error || report.status == RunStatus::Interrupted) {
        result.error = oneLine(diagnostic);
        break;
      }
    if (result.error.empty()) result.error = "the run failed";
    return result;
  }

  if (watch.drawn && !watch.bounds.empty) {
    // The camera the thumbnail was taken with depends on the framed box alone.
    if (!render.framing) render.framing = watch.bounds;
    try {
      const CameraView view = cameraOf(Geometry{}, render);
      const double scale = view.perspective ? view.focal / view.distance : view.focal;
      if (std::isfinite(scale) && scale > 0) result.pixelsPerUnit = scale;
    } catch (const std::invalid_argument&) {
      // A picture size the run refused: no thumbnail, no scale.
    }
  }

  RunQuantities q;
  q.values["cells"] = static_cast<double>(report.cells);
  q.values["time"] = report.time;
  q.values["steps"] = static_cast<double>(report.stats.steps);
  q.values["events"] = static_cast<double>(report.stats.events);
  q.values["born"] = static_cast<double>(report.stats.cellsBorn);
  q.values["firings"] = static_cast<double>(report.stats.ruleFirings);
  if (watch.drawn) addSceneQuantities(watch, q);
  for (const auto& set : run.sets()) {
    if (const auto* geometry = dynamic_cast<const GeometrySet*>(set.get()))
      q.values["length"] = geometry->turtle().drawnLength();
    if (const auto* physics = dynamic_cast<const PhysicsSet*>(set.get())) addPhysicsQuantities(*physics, q);
    if (const auto* creature = dynamic_cast<const CreatureSet*>(set.get())) {
      q.values["distance"] = creature->stats().distance;
      q.values["slip"] = watch.slip;
    }
    if (const auto* dynamics = dynamic_cast<const DynamicsSet*>(set.get())) {
      const DynamicsStats& stats = dynamics->stats();
      q.values["distance"] = std::hypot(stats.root.x - stats.rootStart.x, stats.root.z - stats.rootStart.z);
      q.values["slip"] = stats.slip;
      q.values["fallen"] = stats.simulating && stats.height < stats.startHeight / 2 ? 1 : 0;
      q.values["energy"] = stats.energy;
      q.values["unstable"] = stats.instabilities;
    }
  }
  for (const auto& [name, value] : def.values) q.values[name] = value;
  for (const Measure& measure : def.measures)
    for (const std::string& label : measure.labels()) q.labels.emplace(label, 0);
  if (!q.labels.empty() && run.world()) {
    CellCounter counter(q);
    visitWord(*run.world(), counter);
  }
  for (size_t i = 0; i < def.measures.size(); ++i) {
    const double value = def.measures[i].evaluate(q);
    if (std::isfinite(value)) {
      result.measures[i] = value;
    } else if (result.error.empty()) {
      result.error = "measure " + def.measures[i].name() + " = " + def.measures[i].text() + " is " +
                     (std::isnan(value) ? "not a number" : "infinite");
    }
  }
  return result;
}

}  // namespace ontogen
