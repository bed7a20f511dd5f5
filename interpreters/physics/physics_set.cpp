#include "interpreters/physics/physics_set.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "interpreters/geometry/turtle_commands.h"
#include "interpreters/palette.h"
#include "interpreters/physics/force_arrows.h"
#include "interpreters/physics/rigid_statics.h"
#include "model/random.h"

namespace ontogen {

namespace {

glm::dvec3 toGlm(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d toEigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

bool finite(std::span<const double> args) {
  return std::all_of(args.begin(), args.end(), [](double a) { return std::isfinite(a); });
}

// Palette colour of the external loads: the user colour that reads as "applied" beside
// the blue-to-red ramp of the joints' arrows.
constexpr uint32_t kLoadColor = 5;

}  // namespace

PhysicsSet::PhysicsSet(const PhysicsSetDef& def)
    : def_(def), output_(def.output), turtle_(def.turtle), scratch_(def.mesh), scene_{0, Geometry(def.mesh), {}, {}} {
  if (!(def.g >= 0) || !std::isfinite(def.g)) throw std::invalid_argument("gravity must be a finite number >= 0");
}

bool PhysicsSet::knows(std::string_view command) const {
  return findPhysicsCommand(command) != nullptr || findTurtleCommand(command) != nullptr;
}

void PhysicsSet::beginFrame(const FrameTarget& target) {
  target_ = target;
  turtle_.reset();
  scene_.clear();
  scene_.time = target.time;
  table_.beginFrame(target.time);
  frame_ = PhysicsFrame{};
  frame_.time = target.time;
  frame_.g = def_.g;
  attributes_ = Attributes{};
  attributes_.rod = kNoParentRod;
  stack_.clear();
  pendingLoad_.setZero();
  pendingLoadAt_ = 1;
  hasPendingLoad_ = false;
  segments_ = 0;
  forceScale_ = momentScale_ = 0;
  drawn_ = false;
  drawnShape_.clear();
  queries_.clear();
  answers_.clear();
}

void PhysicsSet::beginCell(const CellContext& cell) {
  cellId_ = cell.id;
  rodsInCell_ = 0;
}

void PhysicsSet::execute(std::string_view command, std::span<const double> args) {
  if (const PhysicsCommand* physics = findPhysicsCommand(command))
    runPhysics(*physics, args);
  else if (const TurtleCommand* turtle = findTurtleCommand(command))
    runTurtle(*turtle, args);
}

void PhysicsSet::executeCommand(int id, std::string_view command, std::span<const double> args) {
  const auto physics = physicsCommands();
  const auto turtle = turtleCommands();
  const auto at = static_cast<size_t>(id);
  if (id >= 0 && at < physics.size())
    runPhysics(physics[at], args);
  else if (id >= 0 && at - physics.size() < turtle.size())
    runTurtle(turtle[at - physics.size()], args);
  else
    execute(command, args);
}

void PhysicsSet::runTurtle(const TurtleCommand& command, std::span<const double> args) {
  const TurtleWarnings before = turtle_.warnings();
  const TurtleState state = turtle_.state();
  const size_t depth = turtle_.depth();
  if (command.op == TurtleOp::Forward || command.op == TurtleOp::Cylinder) {
    // The turtle moves (bent by tropism, stopped by the environment); the rod is drawn
    // at the end of the frame, rest or deflected.
    turtle_.execute(command, args, scratch_);
    scratch_.clear();
    if (turtle_.state().position != state.position) addRod(state.position, state.radius, attributes_.density);
  } else {
    turtle_.execute(command, args, scene_.geometry);
    if (command.op == TurtleOp::Push) stack_.push_back(attributes_);
    if (command.op == TurtleOp::Pop && depth > 0 && !stack_.empty()) {
      attributes_ = stack_.back();
      stack_.pop_back();
    }
  }
  const TurtleWarnings& after = turtle_.warnings();
  unmatchedPops_.add(static_cast<uint64_t>(after.unmatchedPops - before.unmatchedPops), site_);
  badArguments_.add(static_cast<uint64_t>(after.badArguments - before.badArguments), site_);
}

void PhysicsSet::runPhysics(const PhysicsCommand& command, std::span<const double> args) {
  // A query's parameters are what it was answered last; whatever they hold, it asks.
  if (command.op == PhysicsOp::Query) {
    if (attributes_.rod != kNoParentRod) queries_.push_back({cellId_, attributes_.rod, command.name[1]});
    return;
  }
  const auto count = static_cast<int>(args.size());
  if (count < command.minArity || count > command.maxArity || !finite(args)) {
    badArguments_.add(1, site_);
    return;
  }
  switch (command.op) {
    case PhysicsOp::Rod: {
      const double radius = count > 1 ? args[1] : turtle_.state().radius;
      const double density = count > 2 ? args[2] : attributes_.density;
      if (args[0] < 0 || radius < 0 || density < 0) {
        badArguments_.add(1, site_);
        return;
      }
      const glm::dvec3 start = turtle_.state().position;
      static const TurtleCommand& forward = *findTurtleCommand("F");
      const double length[] = {args[0]};
      turtle_.execute(forward, length, scratch_);
      scratch_.clear();
      if (turtle_.state().position != start) addRod(start, radius, density);
      break;
    }
    case PhysicsOp::Density:
      if (args[0] < 0) return badArguments_.add(1, site_);
      attributes_.density = args[0];
      break;
    case PhysicsOp::Load:
      if (count > 3 && (args[3] < 0 || args[3] > 1)) return badArguments_.add(1, site_);
      pendingLoad_ += Eigen::Vector3d(args[0], args[1], args[2]);
      pendingLoadAt_ = count > 3 ? args[3] : 1.0;
      hasPendingLoad_ = true;
      break;
    case PhysicsOp::Young:
      if (!(args[0] > 0)) return badArguments_.add(1, site_);
      attributes_.young = args[0];
      attributes_.stiffness = 0;
      break;
    case PhysicsOp::Stiffness:
      if (args[0] < 0) return badArguments_.add(1, site_);
      attributes_.stiffness = args[0];
      attributes_.young = 0;
      break;
    case PhysicsOp::Elastic:
      if (args[0] < 0 || args[0] > 1024 || args[0] != std::floor(args[0])) return badArguments_.add(1, site_);
      segments_ = static_cast<int>(args[0]);
      break;
    case PhysicsOp::Arrows:
      forceScale_ = args[0];
      momentScale_ = args[1];
      break;
    case PhysicsOp::Query: break;  // answered above
  }
}

// The rod from `base` to where the turtle stands now.
void PhysicsSet::addRod(const glm::dvec3& base, double radius, double density) {
  Rod rod;
  rod.id = rodsInCell_ == 0 ? cellId_ : mixKey(cellId_, static_cast<uint64_t>(rodsInCell_));
  ++rodsInCell_;
  rod.parent = attributes_.rod;
  const TurtleState& state = turtle_.state();
  rod.base = toEigen(base);
  rod.tip = toEigen(state.position);
  rod.radius = radius;
  rod.density = density;
  rod.side = toEigen(state.left);
  rod.material = state.material;
  rod.stiffness = attributes_.stiffness > 0 ? attributes_.stiffness
                  : attributes_.young > 0   ? attributes_.young * std::numbers::pi * std::pow(radius, 4) / 4
                                            : 0;
  if (hasPendingLoad_) {
    rod.load = pendingLoad_;
    rod.loadAt = pendingLoadAt_;
    pendingLoad_.setZero();
    pendingLoadAt_ = 1;
    hasPendingLoad_ = false;
  }
  table_.add(rod);
  attributes_.rod = rod.id;
}

void PhysicsSet::endWord() {
  solve();
  answerQueries();
}

void PhysicsSet::answerQueries() {
  if (queries_.empty()) return;
  std::unordered_map<uint64_t, size_t> indexOf;
  for (size_t i = 0; i < frame_.rods.size(); ++i) indexOf.emplace(frame_.rods[i].id, i);
  for (const NotedQuery& query : queries_) {
    const auto it = indexOf.find(query.rod);
    if (it == indexOf.end()) continue;
    const RodResult& rod = frame_.rods[it->second];
    const Eigen::Vector3d value = query.kind == 'F'   ? rod.force
                                  : query.kind == 'M' ? rod.moment
                                                      : Eigen::Vector3d(rod.tip - rod.restTip);
    // The solver's results are finite (solve() keeps the rigid ones otherwise); a rule
    // must never read what an output could not write.
    if (value.allFinite()) answers_[query.cell] = value;
  }
}

void PhysicsSet::solve() {
  table_.finish();
  const auto rods = table_.rods();
  const std::vector<RodLoads> rigid = solveRigidStatics(rods, table_.leavesFirst(), def_.g);
  frame_.rods.resize(rods.size());
  for (size_t i = 0; i < rods.size(); ++i) {
    const Rod& rod = rods[i];
    frame_.rods[i] = RodResult{rod.id,         rod.parent,      rod.base,       rod.tip,  rod.tip,
                               rod.length(),   rod.mass(),      rigid[i].force, rigid[i].moment,
                               rod.load,       rod.loadPoint()};
  }
  if (segments_ == 0 || rods.empty()) return;
  frame_.elastic = true;
  frame_.segments = segments_;
  ElasticDef def;
  def.segments = segments_;
  def.g = def_.g;
  ElasticSolution elastic = solveElasticRods(rods, table_.leavesFirst(), def);
  frame_.iterations = elastic.iterations;
  bool finiteShape = elastic.converged;
  for (const Eigen::Vector3d& p : elastic.polyline) finiteShape = finiteShape && p.allFinite();
  if (!finiteShape) {
    // The rigid results stay: no number that is not finite reaches an output.
    frame_.converged = false;
    unconverged_.add(1, InstructionSite{{}, {}, frame_.time});
    return;
  }
  for (size_t i = 0; i < rods.size(); ++i) {
    RodResult& result = frame_.rods[i];
    result.base = elastic.base[i];
    result.tip = elastic.tip[i];
    result.force = elastic.loads[i].force;
    result.moment = elastic.loads[i].moment;
  }
  drawnShape_ = std::move(elastic.polyline);
}

namespace {

// The point at `fraction` of a polyline's length.
glm::dvec3 alongPolyline(std::span<const Eigen::Vector3d> points, double fraction) {
  double total = 0;
  for (size_t k = 1; k < points.size(); ++k) total += (points[k] - points[k - 1]).norm();
  double left = std::clamp(fraction, 0.0, 1.0) * total;
  for (size_t k = 1; k < points.size(); ++k) {
    const double piece = (points[k] - points[k - 1]).norm();
    if (left <= piece && piece > 0) return toGlm(points[k - 1] + (left / piece) * (points[k] - points[k - 1]));
    left -= piece;
  }
  return toGlm(points.back());
}

}  // namespace

void PhysicsSet::draw() {
  if (drawn_) return;
  drawn_ = true;
  arrows_.clear();
  const auto rods = table_.rods();
  Geometry& geometry = scene_.geometry;
  const auto points = static_cast<size_t>(2 * frame_.segments + 1);
  const bool deflected = !drawnShape_.empty();
  double longest = 0;
  for (size_t i = 0; i < rods.size(); ++i) {
    const Rod& rod = rods[i];
    longest = std::max(longest, rod.length());
    SceneNode node;
    node.id = rod.id;
    node.parent = rod.parent == kNoParentRod ? kNoParentNode : rod.parent;
    node.position = toGlm(frame_.rods[i].base);
    const glm::dvec3 heading = glm::normalize(toGlm(frame_.rods[i].tip - frame_.rods[i].base));
    const glm::dvec3 side = toGlm(rod.side);
    node.orientation = glm::dmat3(heading, side, glm::cross(heading, side));
    node.range.firstTriangle = static_cast<uint32_t>(geometry.triangleCount());
    node.range.firstSegment = static_cast<uint32_t>(geometry.segmentCount());
    geometry.setMaterial(rod.material);
    auto piece = [&](const glm::dvec3& a, const glm::dvec3& b) {
      if (rod.radius > 0)
        geometry.addCylinder(a, b, rod.radius, /*capped=*/false, side);
      else
        geometry.addSegment(a, b);
    };
    if (deflected) {
      const auto shape = std::span<const Eigen::Vector3d>(drawnShape_).subspan(i * points, points);
      for (size_t k = 1; k < shape.size(); ++k) piece(toGlm(shape[k - 1]), toGlm(shape[k]));
    } else {
      piece(toGlm(rod.base), toGlm(rod.tip));
    }
    node.range.triangleCount = static_cast<uint32_t>(geometry.triangleCount()) - node.range.firstTriangle;
    node.range.segmentCount = static_cast<uint32_t>(geometry.segmentCount()) - node.range.firstSegment;
    scene_.nodes.push_back(node);
  }
  if (rods.empty()) return;

  double largestForce = 0, largestMoment = 0;
  for (const RodResult& rod : frame_.rods) {
    largestForce = std::max({largestForce, rod.force.norm(), rod.load.norm()});
    largestMoment = std::max(largestMoment, rod.moment.norm());
  }
  // Arrows as thick as a small fraction of the longest rod read at any size of tree.
  ArrowStyle style;
  style.shaftRadius = 0.02 * longest;
  style.headLength = 0.1 * longest;
  auto scaleOf = [longest](double fixed, double largest) { return fixed > 0 ? fixed : longest / largest; };
  if (forceScale_ >= 0 && largestForce > 0) {
    const double scale = scaleOf(forceScale_, largestForce);
    for (size_t i = 0; i < rods.size(); ++i) {
      const RodResult& rod = frame_.rods[i];
      const double magnitude = rod.force.norm();
      // Vectors start from the joints, as paper 003 draws them.
      arrows_.push_back({toGlm(rod.base), scale * toGlm(rod.force), magnitude, 1,
                         stressMaterial(magnitude / largestForce), false});
      if (rod.load.norm() > 0) {
        const glm::dvec3 at = deflected ? alongPolyline(std::span<const Eigen::Vector3d>(drawnShape_).subspan(i * points, points),
                                                        rods[i].loadAt)
                                        : toGlm(rod.loadPoint);
        arrows_.push_back({at, scale * toGlm(rod.load), rod.load.norm(), 1, kLoadColor, true});
      }
    }
  }
  if (momentScale_ >= 0 && largestMoment > 0) {
    const double scale = scaleOf(momentScale_, largestMoment);
    for (const RodResult& rod : frame_.rods) {
      const double magnitude = rod.moment.norm();
      arrows_.push_back({toGlm(rod.base), scale * toGlm(rod.moment), magnitude, 2,
                         stressMaterial(magnitude / largestMoment), false});
    }
  }
  for (const DrawnArrow& arrow : arrows_) {
    ArrowStyle drawn = style;
    drawn.heads = arrow.heads;
    drawn.material = arrow.material;
    if (arrow.load) drawn.shaftRadius *= 2;
    addArrow(geometry, arrow.start, arrow.vector, drawn);
  }
}

void PhysicsSet::contribute(Scene& scene) {
  draw();
  scene.time = scene_.time;
  scene.append(scene_);
}

std::vector<std::filesystem::path> PhysicsSet::endFrame() {
  draw();
  return output_.write(scene_, target_);
}

std::vector<SetWarning> PhysicsSet::takeWarnings() {
  std::vector<SetWarning> out;
  unmatchedPops_.takeInto(out, "the turtle ignored " + std::to_string(unmatchedPops_.count) +
                                   " unmatched ']' (the first here)");
  badArguments_.takeInto(out, "the physics set ignored " + std::to_string(badArguments_.count) +
                                  " commands with bad arguments: a wrong count, or values not finite or out of range "
                                  "(the first here)");
  unconverged_.takeInto(out, "the elastic model did not converge in " + std::to_string(unconverged_.count) +
                                 " frames (the first at this time); they keep the rigid shape");
  return out;
}

}  // namespace ontogen
