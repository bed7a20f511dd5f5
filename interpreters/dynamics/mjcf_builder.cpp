#include "interpreters/dynamics/mjcf_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

// A contact with friction in 3 dimensions takes 4 constraint rows (MuJoCo's pyramid).
constexpr int kRowsPerContact = 4;

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
  if (def.iterations < 1 || def.iterations > kMostSolverIterations)
    return "the solver's iterations must be a whole number from 1 to 1000";
  if (!(def.tolerance >= 0 && def.tolerance < 1)) return "the solver's tolerance must be >= 0 and below 1";
  return nullptr;
}

std::string bodyName(int body) { return "b" + std::to_string(body); }
std::string hingeName(int body, int dof) { return "j" + std::to_string(body) + "_" + std::to_string(dof); }
std::string freeName(int body) { return "free" + std::to_string(body); }

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

MujocoRoom mostRoom(const BodyPlan& plan) {
  std::size_t touching = 0, hinges = 0;
  for (const PlanBody& body : plan.bodies) {
    for (const PlanLimb& limb : body.limbs) touching += limb.touches ? 1 : 0;
    hinges += static_cast<std::size_t>(hingeCount(body.kind));
  }
  // MuJoCo meets a plane with at most 2 contacts from a capsule and 4 from a cylinder.
  constexpr std::size_t kContactsPerLimb = 4;
  const MujocoRoom usual = usualRoom(plan);
  const std::size_t contacts = std::max<std::size_t>(static_cast<std::size_t>(usual.contacts), kContactsPerLimb * touching);
  const std::size_t rows = std::max<std::size_t>(static_cast<std::size_t>(usual.rows), kRowsPerContact * contacts + hinges);
  constexpr std::size_t kMost = 1 << 28;
  return {static_cast<int>(std::min(kMost, contacts)), static_cast<int>(std::min(kMost, rows))};
}

uint64_t mujocoRoomBytes(MujocoRoom room) {
  const auto rows = static_cast<uint64_t>(std::max(room.rows, 0));
  return sizeof(double) * (5 * rows * rows + 60 * rows);
}

MujocoRoom doubled(MujocoRoom room, MujocoRoom most) {
  return {std::max(room.contacts, std::min(most.contacts, 2 * room.contacts)),
          std::max(room.rows, std::min(most.rows, 2 * room.rows))};
}

Nesting nestingOf(const BodyPlan& plan, bool centred) {
  const std::size_t n = plan.bodies.size();
  Nesting out;
  out.parent.assign(n, -1);
  out.hinges.resize(n);
  out.free.assign(n, false);
  // A parent comes before its children in a plan; anything else hangs on the world.
  std::vector<int> rootOf(n);
  std::vector<std::vector<int>> neighbours(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int parent = plan.bodies[i].parent;
    const int self = static_cast<int>(i);
    out.hinges[i] = self;
    out.free[i] = plan.bodies[i].kind == JointKind::Free;
    rootOf[i] = self;
    if (parent >= 0 && parent < self) {
      out.parent[i] = parent;
      rootOf[i] = rootOf[static_cast<std::size_t>(parent)];
      neighbours[i].push_back(parent);
      neighbours[static_cast<std::size_t>(parent)].push_back(self);
    }
  }
  std::vector<int> frees(n, 0);  // free bodies per tree
  for (std::size_t i = 0; i < n; ++i)
    if (out.free[i]) ++frees[static_cast<std::size_t>(rootOf[i])];
  std::vector<int> distance(n, -1), previous(n, -1);
  // The body farthest from `from` in its tree (the lowest index among the farthest), its
  // way back in `previous`.
  auto farthest = [&](int from) {
    std::vector<int> queue{from};
    distance[static_cast<std::size_t>(from)] = 0;
    previous[static_cast<std::size_t>(from)] = -1;
    int far = from;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int at = queue[q];
      const int d = distance[static_cast<std::size_t>(at)];
      const int best = distance[static_cast<std::size_t>(far)];
      if (d > best || (d == best && at < far)) far = at;
      for (int next : neighbours[static_cast<std::size_t>(at)])
        if (distance[static_cast<std::size_t>(next)] < 0) {
          distance[static_cast<std::size_t>(next)] = d + 1;
          previous[static_cast<std::size_t>(next)] = at;
          queue.push_back(next);
        }
    }
    for (int at : queue) distance[static_cast<std::size_t>(at)] = -1;
    return far;
  };
  for (std::size_t r = 0; r < n && centred; ++r) {
    const int root = static_cast<int>(r);
    // Only a tree with one free body, its root, hangs from its centre.
    if (out.parent[r] >= 0 || plan.bodies[r].kind != JointKind::Free || frees[r] != 1) continue;
    const int end = farthest(farthest(root));
    std::vector<int> longest;
    for (int at = end; at >= 0; at = previous[static_cast<std::size_t>(at)]) longest.push_back(at);
    const std::size_t length = longest.size();
    const int centre = std::min(longest[(length - 1) / 2], longest[length / 2]);
    // A body without limbs that carries no joint of its own would carry its child's
    // hinges without mass: that tree stays as it is.
    bool massive = true;
    for (int at = centre; at != root; at = plan.bodies[static_cast<std::size_t>(at)].parent) {
      const PlanBody& holder = plan.bodies[static_cast<std::size_t>(plan.bodies[static_cast<std::size_t>(at)].parent)];
      if (hingeCount(plan.bodies[static_cast<std::size_t>(at)].kind) > 0 && holder.kind == JointKind::Weld &&
          holder.limbs.empty())
        massive = false;
    }
    if (!massive || centre == root) continue;
    out.parent[static_cast<std::size_t>(centre)] = -1;
    out.free[static_cast<std::size_t>(centre)] = true;
    out.hinges[static_cast<std::size_t>(centre)] = -1;
    for (int at = centre; at != root;) {
      const int holder = plan.bodies[static_cast<std::size_t>(at)].parent;
      out.parent[static_cast<std::size_t>(holder)] = at;
      out.hinges[static_cast<std::size_t>(holder)] = at;
      out.free[static_cast<std::size_t>(holder)] = false;
      at = holder;
    }
  }
  return out;
}

int nestingDepth(const BodyPlan& plan) {
  const Nesting nesting = nestingOf(plan);
  std::vector<int> depth(plan.bodies.size(), 0);
  int deepest = 0;
  for (std::size_t i = 0; i < plan.bodies.size(); ++i) {
    // Up to the first body whose depth is known, then down again.
    std::vector<int> way;
    int at = static_cast<int>(i);
    while (at >= 0 && depth[static_cast<std::size_t>(at)] == 0) {
      way.push_back(at);
      at = nesting.parent[static_cast<std::size_t>(at)];
    }
    int d = at >= 0 ? depth[static_cast<std::size_t>(at)] : 0;
    for (auto it = way.rbegin(); it != way.rend(); ++it) depth[static_cast<std::size_t>(*it)] = ++d;
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
  return mjcfOf(plan, def, name, room, nestingOf(plan));
}

std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name, MujocoRoom room,
                   const Nesting& nesting) {
  const auto& bodies = plan.bodies;
  std::vector<std::vector<int>> children(bodies.size());
  std::vector<int> roots;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (nesting.parent[i] >= 0)
      children[static_cast<std::size_t>(nesting.parent[i])].push_back(static_cast<int>(i));
    else
      roots.push_back(static_cast<int>(i));
  }

  std::string out;
  out += "<mujoco model=\"" + escaped(name) + "\">\n";
  out += "  <compiler angle=\"radian\" inertiafromgeom=\"true\"/>\n";
  // MuJoCo's Newton solver at every size: on a sparse model (past 60 degrees of freedom)
  // it factors its Hessian sparsely, and on a centred creature that is cheaper than the
  // many iterations of its conjugate gradient (the 64-segment creature walking: two
  // thirds of the time, to a tolerance met in about 4 iterations rather than 21).
  out += "  <option timestep=\"" + number(def.timestep) + "\" gravity=\"0 " + number(-def.gravity) +
         " 0\" integrator=\"" + (def.rungeKutta ? "RK4" : "Euler") + "\" solver=\"Newton\" iterations=\"" +
         std::to_string(def.iterations) + "\" tolerance=\"" + number(def.tolerance) + "\"/>\n";
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
    const int parent = nesting.parent[static_cast<std::size_t>(index)];
    const int owner = nesting.hinges[static_cast<std::size_t>(index)];
    // Placed in its parent's posed frame (every body's frame is its plan orientation at
    // the hinges' kinematic angles): its base frame, the joints turning it from there.
    glm::dvec3 pos = body.position;
    glm::dmat3 frame = owner == index ? body.base : body.orientation;
    // A body hanging the other way round turns, from the child it hangs from, by that
    // child's hinges backwards about the child's joint (at `anchor` in its own frame):
    // with child = it * T * R(q), it = child * R(q)^-1 * T^-1, T^-1 = turn^T then -anchor.
    glm::dvec3 anchor(0.0);
    glm::dmat3 turn(1.0);
    if (parent >= 0 && owner == parent) {
      const PlanBody& child = bodies[static_cast<std::size_t>(parent)];
      const glm::dmat3 inverse = glm::transpose(body.orientation);
      anchor = inverse * (child.position - body.position);
      turn = inverse * child.base;
      frame = glm::transpose(turn);
      pos = -(frame * anchor);
    } else if (parent >= 0) {
      const PlanBody& holder = bodies[static_cast<std::size_t>(parent)];
      const glm::dmat3 inverse = glm::transpose(holder.orientation);
      pos = inverse * (body.position - holder.position);
      frame = inverse * body.base;
    }
    indent(out, depth);
    out += "<body name=\"" + bodyName(index) + "\" pos=\"" + vector(pos) + "\" xyaxes=\"" + vector(frame[0]) + " " +
           vector(frame[1]) + "\">\n";
    if (nesting.free[static_cast<std::size_t>(index)]) {
      indent(out, depth + 1);
      out += "<freejoint name=\"" + freeName(index) + "\"/>\n";
    }
    const PlanBody* hinged = owner >= 0 ? &bodies[static_cast<std::size_t>(owner)] : nullptr;
    const int count = hinged ? hingeCount(hinged->kind) : 0;
    const bool backwards = owner != index;
    for (int k = 0; k < count; ++k) {
      // Backwards: the last hinge first, each about its axis turned into this frame and reversed.
      const int dof = backwards ? count - 1 - k : k;
      const glm::dvec3 axis = backwards ? -(turn * hingeAxis(hinged->kind, dof)) : hingeAxis(hinged->kind, dof);
      const HingeRange& range = hinged->ranges[static_cast<std::size_t>(dof)];
      indent(out, depth + 1);
      out += "<joint name=\"" + hingeName(owner, dof) + "\" type=\"hinge\"";
      if (backwards) out += " pos=\"" + vector(anchor) + "\"";
      out += " axis=\"" + vector(axis) + "\"";
      if (range.set) out += " limited=\"true\" range=\"" + number(range.lo) + " " + number(range.hi) + "\"";
      if (hinged->spring > 0) out += " stiffness=\"" + number(hinged->spring) + "\"";
      if (hinged->damping >= 0) out += " damping=\"" + number(hinged->damping) + "\"";
      out += "/>\n";
      if (def.kp == 0 || !hinged->driven) continue;
      actuators += "    <position name=\"s" + std::to_string(owner) + "_" + std::to_string(dof) + "\" joint=\"" +
                   hingeName(owner, dof) + "\" kp=\"" + number(def.kp) + "\"";
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
