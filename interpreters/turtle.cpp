#include "interpreters/turtle.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

void checkField(const char* field, double value, bool allowNegative) {
  if (!std::isfinite(value) || (!allowNegative && value < 0)) {
    throw std::invalid_argument(std::string("TurtleDef::") + field + " must be finite" +
                                (allowNegative ? "" : " and >= 0") + ", got " +
                                std::to_string(value));
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
}

bool Turtle::execute(std::string_view command, std::span<const double> args,
                     Geometry& geometry) {
  const TurtleCommand* found = findTurtleCommand(command);
  if (found == nullptr) return false;
  execute(*found, args, geometry);
  return true;
}

void Turtle::drawForward(double distance, bool capped, Geometry& geometry) {
  TurtleState& s = state_;
  glm::dvec3 end = s.position + s.heading * distance;
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
      break;
    case TurtleOp::Pop:
      if (stack_.empty()) {
        ++warnings_.unmatchedPops;
      } else {
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
  }
}

}  // namespace ontogen
