#include "interpreters/geometry/turtle.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "interpreters/palette.h"
#include "model/message_number.h"

namespace ontogen {

namespace {

void checkField(const char* field, double value, bool allowNegative) {
  if (!std::isfinite(value) || (!allowNegative && value < 0)) {
    throw std::invalid_argument(std::string("TurtleDef::") + field + " must be finite" +
                                (allowNegative ? "" : " and >= 0") + ", got " +
                                messageNumber(value));
  }
}

bool allFinite(std::span<const double> args) {
  for (double arg : args) {
    if (!std::isfinite(arg)) return false;
  }
  return true;
}

// ABOP's $ takes the vector opposite to gravity; ontogen's world is y-up.
constexpr glm::dvec3 kWorldUp{0.0, 1.0, 0.0};

// Below this |V x H|, H is vertical and no roll makes L horizontal.
constexpr double kVerticalTolerance = 1e-9;

// Sections are numbered 0..1023: ids index a table in a word, not a database.
constexpr int kMaxSectionId = 1023;
constexpr int kMaxCirclePoints = 1024;  // as MeshDef's sides
constexpr int kDefaultCirclePoints = 12;

}  // namespace

Turtle::Turtle(const TurtleDef& def) : def_(def) {
  checkField("step", def.step, true);
  checkField("angle", def.angle, true);
  checkField("yawAngle", def.yawAngle, true);
  checkField("radius", def.radius, false);
  reset();
}

void Turtle::reset() {
  state_ = TurtleState{};
  state_.radius = def_.radius;
  stack_.clear();
  warnings_ = TurtleWarnings{};
  tropism_ = glm::dvec3(0.0);
  tropismStrength_ = 0;
  environment_ = Environment{};
  environmentActive_ = false;
  drawnLength_ = 0;
  sections_.clear();
  circles_.clear();
  definingSection_.reset();
  pendingSection_ = GcSection{};
  gcs_.clear();
  patches_.clear();
  definingPatch_.reset();
  patchPoints_.clear();
  plates_.clear();
  gapTolerance_ = 0;
}

void Turtle::finish(Geometry& geometry) {
  for (std::size_t i = 0; i < gcs_.size(); ++i) {
    if (gcs_[i].open) finishGc(static_cast<int>(i), /*caps=*/true, geometry);
  }
  state_.gc = -1;
  closePlate();
  if (plates_.empty()) return;
  const uint32_t material = geometry.material();
  if (gapTolerance_ > 0) {
    geometry.addMesh(joinPlates(plates_, gapTolerance_).mesh, /*keepMaterials=*/true);
  } else {
    geometry.addMesh(platesAsMesh(plates_), /*keepMaterials=*/true);
  }
  geometry.setMaterial(material);
}

void Turtle::closePlate() {
  if (state_.plate < 0) return;
  if (plates_[static_cast<std::size_t>(state_.plate)].corners.size() < 3) {
    ++warnings_.badArguments;
    plates_.erase(plates_.begin() + state_.plate);
  }
  state_.plate = -1;
}

const Surface* Turtle::surface(int id) const {
  if (auto found = patches_.find(id); found != patches_.end()) return &found->second;
  if (auto found = def_.surfaces.find(id); found != def_.surfaces.end()) return &found->second;
  return nullptr;
}

const Surface& Turtle::surfaceArgument(double id) const {
  const Surface* found = std::isfinite(id) && id == std::round(id) && std::abs(id) <= kMaxSectionId
                             ? surface(static_cast<int>(id))
                             : nullptr;
  if (found == nullptr) {
    std::ostringstream name;
    name << id;
    throw SurfaceError("surface " + name.str() + " is not defined (declare it with #surface ID \"file.obj\", or with patch(ID) ... endpatch "
                       "earlier in the frame)");
  }
  return *found;
}

const GcSection* Turtle::section(int key) {
  if (key >= 0) {
    auto found = sections_.find(key);
    return found == sections_.end() ? nullptr : &found->second;
  }
  auto [it, inserted] = circles_.try_emplace(-key);
  if (inserted) it->second = circleSection(-key);
  return &it->second;
}

void Turtle::finishGc(int index, bool caps, Geometry& geometry) {
  OpenGc& gc = gcs_[static_cast<std::size_t>(index)];
  if (!gc.open) return;
  gc.open = false;
  GcDef def;
  def.caps = caps;
  def.samplesPerSpan = 8;
  uint32_t material = geometry.material();
  geometry.setMaterial(gc.material);
  geometry.addMesh(meshGeneralizedCylinder(gc.points, def));
  geometry.setMaterial(material);
  gc.points.clear();
  gc.points.shrink_to_fit();
}

void Turtle::turnHeadingTo(const glm::dvec3& heading) {
  glm::dvec3& h = state_.heading;
  glm::dvec3 axis = glm::cross(h, heading);
  double sine = glm::length(axis);
  double cosine = glm::dot(h, heading);
  if (sine < 1e-15) {
    if (cosine > 0) return;
    // Opposite: turn around about U.
    h = -h;
    state_.left = -state_.left;
    return;
  }
  axis /= sine;
  auto rotate = [&](const glm::dvec3& v) {
    return v * cosine + glm::cross(axis, v) * sine + axis * glm::dot(axis, v) * (1 - cosine);
  };
  state_.left = rotate(state_.left);
  h = heading;
  orthonormalise();
}

std::optional<double> Turtle::prepareForward(double distance) {
  if (tropismStrength_ != 0) {
    glm::dvec3 h = rotateTowards(state_.heading, tropism_,
                                 tropismStrength_ * glm::length(glm::cross(state_.heading, tropism_)));
    turnHeadingTo(h);
  }
  if (!environmentActive_) return distance;
  if (state_.depth + 1 > environment_.maxDepth) return std::nullopt;
  double left = environment_.maxLength - drawnLength_;
  if (!(left > 0)) return std::nullopt;
  distance = std::min(distance, left);
  turnHeadingTo(environment_.bend(state_.position, state_.heading));
  auto heading = environment_.redirect(state_.position, state_.heading, distance, state_.left, state_.up);
  if (!heading) return std::nullopt;
  turnHeadingTo(*heading);
  return distance;
}

bool Turtle::execute(std::string_view command, std::span<const double> args,
                     Geometry& geometry) {
  const TurtleCommand* found = findTurtleCommand(command);
  if (found == nullptr) return false;
  execute(*found, args, geometry);
  return true;
}

void Turtle::drawForward(double requested, bool capped, Geometry& geometry) {
  auto prepared = prepareForward(requested);
  if (!prepared) {
    ++warnings_.blocked;
    return;
  }
  const double distance = *prepared;
  TurtleState& s = state_;
  glm::dvec3 end = s.position + s.heading * distance;
  drawnLength_ += std::abs(distance);
  s.depth += 1;
  if (s.plate >= 0) {
    s.position = end;
    plates_[static_cast<std::size_t>(s.plate)].corners.push_back(end);
    return;
  }
  if (s.gc >= 0) {
    s.position = end;
    gcs_[static_cast<std::size_t>(s.gc)].points.push_back({end, s.left, s.radius, section(s.section)});
    return;
  }
  if (s.radius > 0) {
    geometry.addCylinder(s.position, end, s.radius, capped, s.left);
  } else {
    geometry.addSegment(s.position, end);
  }
  s.position = end;
}

double Turtle::length(std::span<const double> args) const {
  return args.empty() ? def_.step : args[0];
}

double Turtle::angle(std::span<const double> args, double fallback) const {
  double value = args.empty() ? fallback : args[0];
  return def_.radians ? value : value * (std::numbers::pi / 180.0);
}

void Turtle::rotate(glm::dvec3& a, glm::dvec3& b, double radians) {
  const double c = std::cos(radians);
  const double s = std::sin(radians);
  const glm::dvec3 oldA = a;
  a = oldA * c + b * s;
  b = b * c - oldA * s;
  orthonormalise();
}

void Turtle::orthonormalise() {
  glm::dvec3& h = state_.heading;
  glm::dvec3& l = state_.left;
  h = glm::normalize(h);
  l = glm::normalize(l - h * glm::dot(l, h));
  state_.up = glm::cross(h, l);
}

void Turtle::rollHorizontal() {
  glm::dvec3 left = glm::cross(kWorldUp, state_.heading);
  double size = glm::length(left);
  if (size < kVerticalTolerance) return;
  state_.left = left / size;
  state_.up = glm::cross(state_.heading, state_.left);
}

void Turtle::execute(const TurtleCommand& command, std::span<const double> args,
                     Geometry& geometry) {
  const auto count = static_cast<int>(args.size());
  if (count < command.minArity || count > command.maxArity || !allFinite(args)) {
    ++warnings_.badArguments;
    return;
  }
  TurtleState& s = state_;
  geometry.setMaterial(s.material);
  switch (command.op) {
    case TurtleOp::Forward:
      drawForward(length(args), /*capped=*/false, geometry);
      break;
    case TurtleOp::Move:
      s.position += s.heading * length(args);
      break;
    case TurtleOp::TurnLeft: rotate(s.heading, s.left, angle(args, def_.angle)); break;
    case TurtleOp::TurnRight: rotate(s.heading, s.left, -angle(args, def_.angle)); break;
    case TurtleOp::PitchDown: rotate(s.heading, s.up, -angle(args, def_.angle)); break;
    case TurtleOp::PitchUp: rotate(s.heading, s.up, angle(args, def_.angle)); break;
    case TurtleOp::RollLeft: rotate(s.left, s.up, -angle(args, def_.angle)); break;
    case TurtleOp::RollRight: rotate(s.left, s.up, angle(args, def_.angle)); break;
    case TurtleOp::YawLeft: rotate(s.heading, s.left, angle(args, def_.yawAngle)); break;
    case TurtleOp::YawRight: rotate(s.heading, s.left, -angle(args, def_.yawAngle)); break;
    case TurtleOp::TurnAround:
      // Exact, unlike a rotation by pi.
      s.heading = -s.heading;
      s.left = -s.left;
      break;
    case TurtleOp::Push:
      stack_.push_back(s);
      s.gc = -1;  // a branch does not extend its parent's generalized cylinder
      s.plate = -1;  // nor its plate
      break;
    case TurtleOp::Pop:
      if (stack_.empty()) {
        ++warnings_.unmatchedPops;
      } else {
        if (s.gc >= 0) finishGc(s.gc, /*caps=*/true, geometry);  // the branch's own tube ends
        closePlate();  // and its own plate
        s = stack_.back();
        stack_.pop_back();
      }
      break;
    case TurtleOp::SetRadius:
      if (args[0] < 0) {
        ++warnings_.badArguments;
      } else {
        s.radius = args[0];
      }
      break;
    case TurtleOp::Cylinder:
      // cC moves like F: in the piston of paper 000 (Fig. 5) the connecting rod starts
      // at the piston's end and the crank at the rod's, which closes the mechanism.
      drawForward(length(args), /*capped=*/count > 1 && args[1] != 0, geometry);
      break;
    case TurtleOp::Disc: {
      double inner = count > 1 ? args[0] : 0.0;
      double outer = count > 1 ? args[1] : args[0];
      if (inner < 0 || outer < inner) {
        ++warnings_.badArguments;
      } else {
        geometry.addDisc(s.position, s.heading, s.left, inner, outer);
      }
      break;
    }
    case TurtleOp::Sphere: {
      double radius = count > 0 ? args[0] : s.radius;
      if (radius < 0) {
        ++warnings_.badArguments;
      } else {
        geometry.addSphere(s.position, radius);
      }
      break;
    }
    case TurtleOp::RollHorizontal:
      rollHorizontal();
      break;
    case TurtleOp::Color:
      if (count > 0 && args[0] < 0) {
        ++warnings_.badArguments;
      } else {
        s.material = count > 0 ? static_cast<uint32_t>(std::fmod(std::floor(args[0]), kUserColors))
                               : (s.material + 1) % kUserColors;
      }
      break;
    case TurtleOp::Tropism: {
      glm::dvec3 t(args[0], args[1], args[2]);
      if (glm::length(t) == 0 && args[3] != 0) {
        ++warnings_.badArguments;
      } else {
        // T as given, not its direction: its length scales the bend, as in ABOP 2.4.
        tropism_ = args[3] == 0 ? glm::dvec3(0.0) : t;
        tropismStrength_ = args[3];
      }
      break;
    }
    case TurtleOp::Circle:
    case TurtleOp::Section:
    case TurtleOp::Point:
    case TurtleOp::EndSection:
    case TurtleOp::UseSection:
    case TurtleOp::GcBegin:
    case TurtleOp::GcEnd:
      executeCylinderCommand(command.op, args, geometry);
      break;
    case TurtleOp::Ceiling:
    case TurtleOp::Ground:
    case TurtleOp::ObstacleSphere:
    case TurtleOp::ObstacleBox:
    case TurtleOp::Attractor:
    case TurtleOp::Repeller:
    case TurtleOp::MaxLength:
    case TurtleOp::MaxDepth:
      executeEnvironment(command.op, args);
      break;
    case TurtleOp::PlaceSurface:
    case TurtleOp::BlendSurfaces:
    case TurtleOp::Patch:
    case TurtleOp::PatchPoint:
    case TurtleOp::EndPatch:
    case TurtleOp::Plate:
    case TurtleOp::EndPlate:
    case TurtleOp::GapFilter:
      executeSurfaceCommand(command.op, args, geometry);
      break;
    case TurtleOp::Query:
      break;  // a query draws nothing; the turtle environment reads the frame here
  }
}

void Turtle::placeSurface(const Surface& surface, double scale, Geometry& geometry) {
  const TurtleState& s = state_;
  SurfacePlacement placement{s.position, glm::cross(s.heading, s.up), s.heading, s.up, scale};
  geometry.addMesh(ontogen::placeSurface(surface, placement));
}

void Turtle::executeSurfaceCommand(TurtleOp op, std::span<const double> args, Geometry& geometry) {
  TurtleState& s = state_;
  switch (op) {
    case TurtleOp::PlaceSurface: {
      const Surface& surface = surfaceArgument(args[0]);
      const double scale = args.size() > 1 ? args[1] : 1.0;
      if (!(scale > 0)) {
        ++warnings_.badArguments;
        return;
      }
      placeSurface(surface, scale, geometry);
      break;
    }
    case TurtleOp::BlendSurfaces: {
      if (args.size() % 2 == 0 || !(args[0] > 0)) {
        ++warnings_.badArguments;
        return;
      }
      std::vector<const Surface*> surfaces;
      std::vector<double> weights;
      for (std::size_t k = 1; k + 1 < args.size(); k += 2) {
        surfaces.push_back(&surfaceArgument(args[k]));
        weights.push_back(args[k + 1]);
      }
      placeSurface(blendSurfaces(surfaces, weights), args[0], geometry);
      break;
    }
    case TurtleOp::Patch: {
      const double id = std::round(args[0]);
      const double resolution = args.size() > 1 ? std::round(args[1]) : 8.0;
      if (id < 0 || id > kMaxSectionId || resolution < 1 || resolution > 256) {
        ++warnings_.badArguments;
        return;
      }
      definingPatch_ = static_cast<int>(id);
      patchResolution_ = static_cast<int>(resolution);
      patchPoints_.clear();
      break;
    }
    case TurtleOp::PatchPoint:
      if (!definingPatch_ || patchPoints_.size() >= 16) {
        ++warnings_.badArguments;
      } else {
        patchPoints_.emplace_back(args[0], args[1], args[2]);
      }
      break;
    case TurtleOp::EndPatch:
      if (!definingPatch_ || patchPoints_.size() != 16) {
        ++warnings_.badArguments;
      } else {
        PatchControls controls;
        std::copy(patchPoints_.begin(), patchPoints_.end(), controls.begin());
        patches_[*definingPatch_] = bezierPatch(controls, patchResolution_);
      }
      definingPatch_.reset();
      patchPoints_.clear();
      break;
    case TurtleOp::Plate:
      closePlate();
      s.plate = static_cast<int>(plates_.size());
      plates_.push_back(Plate{{s.position}, s.material});
      break;
    case TurtleOp::EndPlate:
      if (s.plate < 0) {
        ++warnings_.badArguments;
      } else {
        closePlate();
      }
      break;
    case TurtleOp::GapFilter:
      if (args[0] < 0) {
        ++warnings_.badArguments;
      } else {
        gapTolerance_ = args[0];
      }
      break;
    default:
      break;
  }
}

void Turtle::executeCylinderCommand(TurtleOp op, std::span<const double> args, Geometry& geometry) {
  TurtleState& s = state_;
  switch (op) {
    case TurtleOp::Circle: {
      double points = args.empty() ? kDefaultCirclePoints : std::round(args[0]);
      if (points < 3 || points > kMaxCirclePoints) {
        ++warnings_.badArguments;
      } else {
        s.section = -static_cast<int>(points);
      }
      break;
    }
    case TurtleOp::Section: {
      double id = std::round(args[0]);
      if (id < 0 || id > kMaxSectionId) {
        ++warnings_.badArguments;
      } else {
        definingSection_ = static_cast<int>(id);
        pendingSection_ = GcSection{};
      }
      break;
    }
    case TurtleOp::Point:
      if (!definingSection_) {
        ++warnings_.badArguments;
      } else {
        pendingSection_.points.emplace_back(args[0], args[1]);
      }
      break;
    case TurtleOp::EndSection:
      if (!definingSection_ || pendingSection_.points.size() < 3) {
        ++warnings_.badArguments;
      } else {
        sections_[*definingSection_] = std::move(pendingSection_);
      }
      definingSection_.reset();
      pendingSection_ = GcSection{};
      break;
    case TurtleOp::UseSection: {
      double id = std::round(args[0]);
      if (id < 0 || id > kMaxSectionId || !sections_.contains(static_cast<int>(id))) {
        ++warnings_.badArguments;
      } else {
        s.section = static_cast<int>(id);
      }
      break;
    }
    case TurtleOp::GcBegin:
      if (s.gc >= 0) finishGc(s.gc, /*caps=*/true, geometry);
      s.gc = static_cast<int>(gcs_.size());
      gcs_.push_back(OpenGc{{{s.position, s.left, s.radius, section(s.section)}}, s.material, true});
      break;
    case TurtleOp::GcEnd:
      if (s.gc < 0) {
        ++warnings_.badArguments;
      } else {
        finishGc(s.gc, args.empty() || args[0] != 0, geometry);
        s.gc = -1;
      }
      break;
    default:
      break;
  }
}

void Turtle::executeEnvironment(TurtleOp op, std::span<const double> args) {
  Environment& e = environment_;
  switch (op) {
    case TurtleOp::Ceiling: e.ceiling = args[0]; break;
    case TurtleOp::Ground: e.ground = args[0]; break;
    case TurtleOp::ObstacleSphere:
      if (args[3] <= 0) {
        ++warnings_.badArguments;
        return;
      }
      e.spheres.push_back({{args[0], args[1], args[2]}, args[3]});
      break;
    case TurtleOp::ObstacleBox: {
      glm::dvec3 a(args[0], args[1], args[2]), b(args[3], args[4], args[5]);
      e.boxes.push_back({glm::min(a, b), glm::max(a, b)});
      break;
    }
    case TurtleOp::Attractor:
    case TurtleOp::Repeller:
      if (args[3] < 0 || args[4] <= 0) {
        ++warnings_.badArguments;
        return;
      }
      e.influences.push_back({{args[0], args[1], args[2]}, op == TurtleOp::Attractor ? args[3] : -args[3], args[4]});
      break;
    case TurtleOp::MaxLength:
      if (args[0] < 0) {
        ++warnings_.badArguments;
        return;
      }
      e.maxLength = args[0];
      break;
    case TurtleOp::MaxDepth:
      if (args[0] < 0) {
        ++warnings_.badArguments;
        return;
      }
      e.maxDepth = std::floor(args[0]);
      break;
    default:
      return;
  }
  environmentActive_ = !e.empty();
}

}  // namespace ontogen
