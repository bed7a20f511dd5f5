// The JSON of `ontogen statics` and the equation writer: the fields the documentation
// names, in world coordinates; equations that hold when the solution is put in them.

#include "interpreters/physics/statics_output.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "core/salts.h"
#include "tests/interpreters/physics/physics_support.h"

namespace ontogen {
namespace {

using testing_support::solveModel;

Eigen::Vector3d vectorOf(const nlohmann::json& v) { return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}; }

TEST(StaticsOutput, TheJsonHoldsEveryRodWithTheDocumentedFields) {
  const auto solved = solveModel("statics_binary_tree.cell");
  std::ostringstream text;
  writeStaticsJson(text, solved.frame());
  const nlohmann::json json = nlohmann::json::parse(text.str());
  EXPECT_EQ(json["t"].get<double>(), 4);
  EXPECT_EQ(json["g"].get<double>(), 9.81);
  ASSERT_EQ(json["rods"].size(), 15u);
  for (size_t i = 0; i < json["rods"].size(); ++i) {
    const auto& rod = json["rods"][i];
    const RodResult& solvedRod = solved.frame().rods[i];
    EXPECT_EQ(rod.size(), 9u) << rod.dump();
    EXPECT_EQ(rod["id"].get<uint64_t>(), solvedRod.id & kIdBits);  // as word --json prints ids
    if (i == 0)
      EXPECT_EQ(rod["parent"].get<int>(), -1);
    else
      EXPECT_EQ(rod["parent"].get<uint64_t>(), solvedRod.parent & kIdBits);
    EXPECT_EQ(vectorOf(rod["tip"]), vectorOf(rod["rest_tip"])) << "rigid rods do not bend";
    EXPECT_EQ(vectorOf(rod["force"]), solvedRod.force) << "the shortest exact form reads back as the same double";
    EXPECT_EQ(vectorOf(rod["moment"]), solvedRod.moment);
    EXPECT_NEAR((vectorOf(rod["tip"]) - vectorOf(rod["base"])).norm(), rod["length"].get<double>(), 1e-12);
    EXPECT_EQ(rod["mass"].get<double>(), solvedRod.mass);
  }
  EXPECT_EQ(vectorOf(json["rods"][0]["base"]), Eigen::Vector3d::Zero());
  EXPECT_NEAR(json["rods"][0]["tip"][1].get<double>(), 5, 1e-12) << "the root stands 5 m up the y axis";
}

TEST(StaticsOutput, NonFiniteResultsAreRefused) {
  PhysicsFrame frame;
  frame.rods.push_back(RodResult{});
  frame.rods[0].force.x() = INFINITY;
  std::ostringstream text;
  EXPECT_THROW(writeStaticsJson(text, frame), NonFiniteResult);
  EXPECT_TRUE(text.str().empty()) << "nothing is written";
}

// Reads "(a, b, c)" at `at`, moving past it.
Eigen::Vector3d readTuple(const std::string& line, size_t& at) {
  at = line.find('(', at);
  const size_t end = line.find(')', at);
  std::istringstream in(line.substr(at + 1, end - at - 1));
  Eigen::Vector3d v;
  char comma;
  in >> v.x() >> comma >> v.y() >> comma >> v.z();
  at = end + 1;
  return v;
}

// Every equation the writer prints holds with the solver's F and M substituted.
TEST(StaticsOutput, TheEquationsHoldForTheSolution) {
  for (const char* model : {"statics_binary_tree.cell", "statics_spiral.cell", "statics_quad_tree.cell"}) {
    SCOPED_TRACE(model);
    const auto solved = solveModel(model);
    std::map<std::string, Eigen::Vector3d> value;
    for (const RodResult& rod : solved.frame().rods) {
      value["F_" + std::to_string(rod.id & kIdBits)] = rod.force;
      value["M_" + std::to_string(rod.id & kIdBits)] = rod.moment;
    }
    std::ostringstream text;
    writeStaticsEquations(text, solved.set->table(), kGravity, solved.frame().time);
    std::istringstream lines(text.str());
    std::string line;
    int equations = 0;
    while (std::getline(lines, line)) {
      if (line.empty() || line[0] == '#') continue;
      ++equations;
      const std::string lhs = line.substr(0, line.find(' '));
      size_t at = 0;
      Eigen::Vector3d sum = readTuple(line, at);
      // The rest: " + F_k" or " + (l) x F_k + M_k".
      while (at < line.size()) {
        at = line.find("+ ", at) + 2;
        if (line[at] == '(') {
          const Eigen::Vector3d lever = readTuple(line, at);
          at = line.find("F_", at);
          const size_t end = line.find(' ', at);
          sum += lever.cross(value.at(line.substr(at, end - at)));
          at = end;
        } else {
          const size_t end = line.find(' ', at);
          sum += value.at(line.substr(at, end == std::string::npos ? std::string::npos : end - at));
          at = end == std::string::npos ? line.size() : end;
        }
      }
      const Eigen::Vector3d& solution = value.at(lhs);
      EXPECT_LT((sum - solution).norm(), 1e-9 * std::max(1.0, solution.norm())) << line;
    }
    EXPECT_EQ(equations, 2 * static_cast<int>(solved.frame().rods.size()));
  }
}

}  // namespace
}  // namespace ontogen
