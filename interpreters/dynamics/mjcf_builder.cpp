#include "interpreters/dynamics/mjcf_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

// A contact with friction in 3 dimensions takes 4 constraint rows (MuJoCo's pyramid).
constexpr int kRowsPerContact = 4;
// MuJoCo 2.2's Newton solver factors a dense Hessian of the degrees of freedom at each
// step; past this many, its conjugate gradient is the cheaper (the 64-segment creature,
// 646 degrees of freedom: 3.1 ms a step in the constraint solver against Newton's 6.4).
constexpr int kNewtonDegrees = 100;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string vector(const glm::dvec3& v) { return number(v.x) + " " + number(v.y) + " " + number(v.z); }

// An XML attribute's text from the model's name: the five characters XML reserves escaped.
std::string escaped(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

void indent(std::string& out, int depth) { out.append(static_cast<std::size_t>(2 * depth), ' '); }

}  // namespace

const char* physicsError(const PhysicsDef& def) {
  if (!(def.timestep > 0) || !std::isfinite(def.timestep)) return "the simulation's timestep must be above 0";
  if (!(def.gravity >= 0) || !std::isfinite(def.gravity)) return "gravity must be a finite number >= 0";
  if (!std::isfinite(def.ground)) return "the ground's height must be finite";
  if (!(def.density > 0) || !std::isfinite(def.density)) return "the density must be a finite number above 0";
  if (!(def.friction >= 0) || !std::isfinite(def.friction)) return "the friction must be a finite number >= 0";
  if (!(def.kp >= 0) || !std::isfinite(def.kp)) return "the servos' kp must be a finite number >= 0";
  if (!(def.kd >= 0) || !std::isfinite(def.kd)) return "the servos' kd must be a finite number >= 0";
  if (!(def.torque > 0)) return "the servos' torque must be above 0";
  return nullptr;
}

std::string bodyName(int body) { return "b" + std::to_string(body); }
std::string hingeName(int body, int dof) { return "j" + std::to_string(body) + "_" + std::to_string(dof); }

MujocoRoom usualRoom(const BodyPlan& plan) {
  std::size_t limbs = 0, limits = 0;
  for (const PlanBody& body : plan.bodies) {
    limbs += body.limbs.size();
    for (int dof = 0; dof < hingeCount(body.kind); ++dof) limits += body.ranges[static_cast<std::size_t>(dof)].set ? 1 : 0;
  }
  constexpr std::size_t kMost = 1 << 20;  // beyond this the plan is far past the set's limits
  const std::size_t contacts = std::clamp<std::size_t>(limbs, 16, kMost);
  return {static_cast<int>(contacts), static_cast<int>(std::min(kMost, kRowsPerContact * contacts + limits))};
}

MujocoRoom doubled(MujocoRoom room) {
  constexpr int kMost = 1 << 28;
  return {std::min(kMost, 2 * room.contacts), std::min(kMost, 2 * room.rows)};
}

int nestingDepth(const BodyPlan& plan) {
  // A parent comes before its children in a plan.
  std::vector<int> depth(plan.bodies.size(), 1);
  int deepest = 0;
  for (std::size_t i = 0; i < plan.bodies.size(); ++i) {
    const int parent = plan.bodies[i].parent;
    if (parent >= 0 && static_cast<std::size_t>(parent) < i) depth[i] = depth[static_cast<std::size_t>(parent)] + 1;
    deepest = std::max(deepest, depth[i]);
  }
  return deepest;
}

std::string sizeElement(MujocoRoom room) {
  return "<size nconmax=\"" + std::to_string(room.contacts) + "\" njmax=\"" + std::to_string(room.rows) + "\"/>";
}

std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name) {
  return mjcfOf(plan, def, name, usualRoom(plan));
}

std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name, MujocoRoom room) {
  const auto& bodies = plan.bodies;
  std::vector<std::vector<int>> children(bodies.size());
  std::vector<int> roots;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].parent >= 0)
      children[static_cast<std::size_t>(bodies[i].parent)].push_back(static_cast<int>(i));
    else
      roots.push_back(static_cast<int>(i));
  }

  std::string out;
  out += "<mujoco model=\"" + escaped(name) + "\">\n";
  out += "  <compiler angle=\"radian\" inertiafromgeom=\"true\"/>\n";
  int degrees = 0;
  for (const PlanBody& body : bodies) degrees += body.kind == JointKind::Free ? 6 : hingeCount(body.kind);
  out += "  <option timestep=\"" + number(def.timestep) + "\" gravity=\"0 " + number(-def.gravity) +
         " 0\" integrator=\"" + (def.rungeKutta ? "RK4" : "Euler") + "\"" +
         (degrees > kNewtonDegrees ? " solver=\"CG\"" : "") + "/>\n";
  out += "  " + sizeElement(room) + "\n";
  // Limbs touch the ground and nothing else: contype 0 meets conaffinity 1 of the ground only.
  out += "  <default>\n    <geom contype=\"0\" conaffinity=\"1\" condim=\"3\" friction=\"" + number(def.friction) +
         " 0.005 0.0001\" density=\"" + number(def.density) + "\"/>\n";
  out += "    <joint damping=\"" + number(def.kd) + "\"/>\n  </default>\n";
  out += "  <worldbody>\n";
  out += "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" pos=\"0 " + number(def.ground) +
         " 0\" xyaxes=\"1 0 0 0 0 -1\" contype=\"1\" conaffinity=\"1\"/>\n";

  std::string actuators;
  const bool limited = std::isfinite(def.torque);
  // Depth first, so a body's children are written inside it.
  auto write = [&](auto&& self, int index, int depth) -> void {
    const PlanBody& body = bodies[static_cast<std::size_t>(index)];
    // Placed in its parent's posed frame (its parent's hinges at their kinematic angles).
    glm::dvec3 pos = body.position;
    glm::dmat3 frame = body.base;
    if (body.parent >= 0) {
      const PlanBody& parent = bodies[static_cast<std::size_t>(body.parent)];
      const glm::dmat3 inverse = glm::transpose(parent.orientation);
      pos = inverse * (body.position - parent.position);
      frame = inverse * body.base;
    }
    indent(out, depth);
    out += "<body name=\"" + bodyName(index) + "\" pos=\"" + vector(pos) + "\" xyaxes=\"" + vector(frame[0]) + " " +
           vector(frame[1]) + "\">\n";
    if (body.kind == JointKind::Free) {
      indent(out, depth + 1);
      out += "<freejoint name=\"" + hingeName(index, 0) + "\"/>\n";
    }
    for (int dof = 0; dof < hingeCount(body.kind); ++dof) {
      const HingeRange& range = body.ranges[static_cast<std::size_t>(dof)];
      indent(out, depth + 1);
      out += "<joint name=\"" + hingeName(index, dof) + "\" type=\"hinge\" axis=\"" + vector(hingeAxis(body.kind, dof)) +
             "\"";
      if (range.set) out += " limited=\"true\" range=\"" + number(range.lo) + " " + number(range.hi) + "\"";
      if (body.spring > 0) out += " stiffness=\"" + number(body.spring) + "\"";
      if (body.damping >= 0) out += " damping=\"" + number(body.damping) + "\"";
      out += "/>\n";
      if (def.kp == 0 || !body.driven) continue;
      actuators += "    <position name=\"s" + std::to_string(index) + "_" + std::to_string(dof) + "\" joint=\"" +
                   hingeName(index, dof) + "\" kp=\"" + number(def.kp) + "\"";
      if (limited) actuators += " forcelimited=\"true\" forcerange=\"" + number(-def.torque) + " " + number(def.torque) + "\"";
      actuators += "/>\n";
    }
    // Limbs in the body's frame with its hinges at their kinematic angles.
    const glm::dmat3 inverse = glm::transpose(body.orientation);
    for (const PlanLimb& limb : body.limbs) {
      indent(out, depth + 1);
      out += std::string("<geom type=\"") + (limb.cylinder ? "cylinder" : "capsule") + "\" size=\"" +
             number(limb.radius) + "\" fromto=\"" + vector(inverse * (limb.start - body.position)) + " " +
             vector(inverse * (limb.end - body.position)) + "\"";
      if (limb.density > 0) out += " density=\"" + number(limb.density) + "\"";
      if (!limb.touches) out += " conaffinity=\"0\"";
      out += "/>\n";
    }
    // A body that moves needs a mass: a small ball where it has no limb.
    if (body.limbs.empty() && body.kind != JointKind::Weld) {
      indent(out, depth + 1);
      out += "<geom type=\"sphere\" size=\"0.02\" contype=\"0\" conaffinity=\"0\"/>\n";
    }
    for (int child : children[static_cast<std::size_t>(index)]) self(self, child, depth + 1);
    indent(out, depth);
    out += "</body>\n";
  };
  for (int root : roots) write(write, root, 2);
  out += "  </worldbody>\n";
  if (!actuators.empty()) out += "  <actuator>\n" + actuators + "  </actuator>\n";
  out += "</mujoco>\n";
  return out;
}

}  // namespace ontogen
