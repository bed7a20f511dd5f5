#include "interpreters/physics/statics_output.h"

#include <charconv>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "core/salts.h"
#include "interpreters/physics/rigid_statics.h"

namespace ontogen {

namespace {

// The shortest text that reads back as the same double.
std::string number(double value) {
  if (!std::isfinite(value)) throw NonFiniteResult("a result is not a finite number");
  if (value == 0) value = 0;  // no "-0": the same bytes for the same physics
  char buffer[32];
  auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  (void)error;
  return std::string(buffer, end);
}

std::string vector(const Eigen::Vector3d& v) {
  return "[" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + "]";
}

std::string tuple(const Eigen::Vector3d& v) {
  return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")";
}

// A rod's id as `word --json` prints the cell's (its low 53 bits, which a JSON reader
// holds exactly), so that the two outputs join on it.
std::string idText(uint64_t id) { return std::to_string(id & kIdBits); }

}  // namespace

void writeStaticsJson(std::ostream& out, const PhysicsFrame& frame) {
  std::string text = "{\"t\": " + number(frame.time) + ", \"g\": " + number(frame.g) + ", \"rods\": [";
  for (size_t i = 0; i < frame.rods.size(); ++i) {
    const RodResult& rod = frame.rods[i];
    text += i ? ",\n  " : "\n  ";
    text += "{\"id\": " + idText(rod.id) + ", \"parent\": " +
            (rod.parent == kNoParentRod ? std::string("-1") : idText(rod.parent)) +
            ", \"base\": " + vector(rod.base) + ", \"tip\": " + vector(rod.tip) + ", \"rest_tip\": " +
            vector(rod.restTip) + ", \"length\": " + number(rod.length) + ", \"mass\": " + number(rod.mass) +
            ", \"force\": " + vector(rod.force) + ", \"moment\": " + vector(rod.moment) + "}";
  }
  text += frame.rods.empty() ? "]}\n" : "\n]}\n";
  out << text;
}

void writeStaticsEquations(std::ostream& out, const RodTable& table, double g, double time) {
  const auto rods = table.rods();
  std::string text = "# The statics of a rigid rod tree (paper 003, Eq. 1 and Eq. 2) at t = " + number(time) +
                     " s: F_i is the force on rod i's base joint (N), M_i its moment about that base (N m);\n"
                     "# i is the cell id; g = " +
                     number(g) + " m/s^2 along -y; the known terms (weight and external force) are evaluated.\n";
  for (size_t i = 0; i < rods.size(); ++i) {
    const Rod& rod = rods[i];
    const Eigen::Vector3d weight = weightOf(rod, g);
    const Eigen::Vector3d force = weight + rod.load;
    const Eigen::Vector3d moment =
        (0.5 * (rod.tip - rod.base)).cross(weight) + (rod.loadPoint() - rod.base).cross(rod.load);
    const std::string id = idText(rod.id);
    std::string f = "F_" + id + " = " + tuple(force);
    std::string m = "M_" + id + " = " + tuple(moment);
    for (int child : table.children(static_cast<int>(i))) {
      const Rod& c = rods[static_cast<size_t>(child)];
      const std::string k = idText(c.id);
      f += " + F_" + k;
      m += " + " + tuple(c.base - rod.base) + " x F_" + k + " + M_" + k;
    }
    text += f + "\n" + m + "\n";
  }
  out << text;
}

}  // namespace ontogen
