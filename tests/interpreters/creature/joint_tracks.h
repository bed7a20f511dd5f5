#pragma once
// A creature's run read back for tests: its report, its joints' tracks (joints.json:
// the joints with their parents and feet, each frame's time and positions) and where
// they were written. The creature's and the dynamics set's tests share it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "interpreters/run.h"

namespace ontogen::test {

struct Walk {
  // The program run, kept: the report's diagnostics point into its source text.
  std::shared_ptr<const Program> program;
  RunReport report;
  nlohmann::json tracks;  // the joints.json
  std::filesystem::path dir;

  const nlohmann::json& joints() const { return tracks["joints"]; }
  const nlohmann::json& frames() const { return tracks["frames"]; }
  glm::dvec3 at(std::size_t frame, std::size_t joint) const {
    const auto& p = tracks["frames"][frame]["positions"][joint];
    return {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
  }
  double time(std::size_t frame) const { return tracks["frames"][frame]["t"].get<double>(); }
  std::vector<std::size_t> feet() const {
    std::vector<std::size_t> out;
    for (std::size_t j = 0; j < joints().size(); ++j)
      if (joints()[j]["foot"].get<bool>()) out.push_back(j);
    return out;
  }
  std::size_t root() const {
    for (std::size_t j = 0; j < joints().size(); ++j)
      if (joints()[j]["parent"].get<int>() < 0) return j;
    return 0;
  }
  // The root's travel along the ground from the first frame to the last.
  double distance() const {
    const glm::dvec3 a = at(0, root()), b = at(frames().size() - 1, root());
    return std::hypot(b.x - a.x, b.z - a.z);
  }
  // The lowest height any joint reached in any frame.
  double lowest() const {
    double low = 1e300;
    for (std::size_t f = 0; f < frames().size(); ++f)
      for (std::size_t j = 0; j < joints().size(); ++j) low = std::min(low, at(f, j).y);
    return low;
  }
};

}  // namespace ontogen::test
