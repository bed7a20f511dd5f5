// The ontogen executable as a user meets it: exit codes, messages, files written.

#include <cstdlib>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include "tests/apps/ontogen_process.h"
#include "tests/checkers.h"

namespace {

namespace fs = std::filesystem;

using Result = ontogen::test::OntogenRun;

fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "cli_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

using ontogen::test::runOntogenShell;  // `ontogen ARGS` through the shell

std::string model(const std::string& name) { return std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name; }

fs::path writeProgram(const fs::path& dir, const std::string& text) {
  fs::path path = dir / "program.cell";
  std::ofstream(path) << text;
  return path;
}

TEST(Cli, CheckAcceptsEveryModel) {
  for (const auto& entry : fs::directory_iterator(std::string(ONTOGEN_SOURCE_DIR) + "/models")) {
    if (entry.path().extension() != ".cell") continue;
    Result result = runOntogenShell("check " + entry.path().string());
    EXPECT_EQ(result.exitCode, 0) << entry.path() << "\n" << result.err;
    EXPECT_NE(result.out.find(": ok"), std::string::npos);
  }
}

TEST(Cli, BadProgramGivesLocatedErrorsAndWritesNothing) {
  fs::path dir = scratch("bad");
  fs::path program = writeProgram(dir, "lsystem a {\n  axiom A(1)\n  A(x) -> A(y + 1)\n  A(x) -> B(sin())\n}\n");
  fs::path out = dir / "out";
  Result result = runOntogenShell("run " + program.string() + " --out " + out.string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find(program.string() + ":3:13: error: unknown name 'y'\n  A(x) -> A(y + 1)\n            ^\n"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find(":4:13: error: 'sin' takes 1 argument"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("2 errors in"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, WordJsonReproducesTable1OfPaper000) {
  Result result = runOntogenShell("word " + model("piston.cell") + " --at 0,0.04,1.04,4.04 --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  auto json = nlohmann::json::parse(result.out);
  ASSERT_EQ(json["times"].size(), 4u);
  EXPECT_EQ(json["times"][0]["cells"][0]["label"], "piston");
  const auto& at104 = json["times"][2];
  EXPECT_DOUBLE_EQ(at104["t"].get<double>(), 1.04);
  const auto& cells = at104["cells"];
  ASSERT_EQ(cells.size(), 12u);
  EXPECT_EQ(cells[0]["label"], "mov");
  EXPECT_NEAR(cells[0]["developed"][0].get<double>(), 50, 1e-9);
  EXPECT_NEAR(cells[0]["params"][0].get<double>(), 50, 0);
  EXPECT_NEAR(cells[0]["age"].get<double>(), 1, 1e-9);
  EXPECT_NEAR(cells[3]["developed"][0].get<double>(), std::asin(0.25), 1e-12);
  EXPECT_NEAR(cells[6]["developed"][0].get<double>(), std::asin(0.25) + M_PI / 2, 1e-12);
  EXPECT_EQ(cells[1]["label"], "!");
  EXPECT_EQ(cells[1]["developed"], nlohmann::json::parse("[10]"));
}

// The piston's word at t = 4.04, pinned by value: every id, parent, age and parameter as
// `word --json` prints them. mov, bend and turn were just replaced (age 0, new ids); the
// rest keep the ids and births they got at t = 0.04. Nothing here may move when the
// linear pool's storage changes (docs/COMPACT_WORDS.md, section 7, slice 0).
TEST(Cli, WordJsonOfThePistonAt4_04IsPinned) {
  Result result = runOntogenShell("word " + model("piston.cell") + " --at 4.04 --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, R"JSON({"times": [
  {"t": 4.04, "cells": [
    {"label": "mov", "params": [50], "developed": [0], "age": 0, "id": 8719005630369449, "parent": -1},
    {"label": "!", "params": [10], "developed": [10], "age": 4, "id": 1412667277046589, "parent": 8719005630369449},
    {"label": "cC", "params": [60, 1], "developed": [60, 1], "age": 4, "id": 3955507135847856, "parent": 8719005630369449},
    {"label": "bend", "params": [2], "developed": [0], "age": 0, "id": 3008876155874388, "parent": 3955507135847856},
    {"label": "!", "params": [2], "developed": [2], "age": 4, "id": 7439240056358614, "parent": 3008876155874388},
    {"label": "cC", "params": [200, 1], "developed": [200, 1], "age": 4, "id": 3173683470804916, "parent": 3008876155874388},
    {"label": "turn", "params": [1], "developed": [0], "age": 0, "id": 3439578793272120, "parent": 3173683470804916},
    {"label": "f", "params": [50], "developed": [50], "age": 4, "id": 3106933542404335, "parent": 3439578793272120},
    {"label": "+", "params": [1.5707963267948966], "developed": [1.5707963267948966], "age": 4, "id": 7263828583646127, "parent": 3106933542404335},
    {"label": "[", "params": [], "developed": [], "age": 4, "id": 444317092373405, "parent": 3106933542404335},
    {"label": "disc", "params": [0, 50], "developed": [0, 50], "age": 4, "id": 608078555481270, "parent": 3106933542404335},
    {"label": "]", "params": [], "developed": [], "age": 4, "id": 1575216515794220, "parent": 3106933542404335}
  ]}
]}
)JSON");
}

TEST(Cli, WordTextInTheStyleOfTable1) {
  Result result = runOntogenShell("word " + model("piston.cell") + " --at 1.04 --precision 3");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1.04: (mov(50), 1) !(10) cC(60, 1) (bend(0.253), 1) !(2) cC(200, 1) (turn(1.82), 1) f(50) "
            "+(1.57) [ disc(0, 50) ]\n");
}

TEST(Cli, RunWritesOneNumberedOutputPerFrame) {
  fs::path out = scratch("frames");
  Result result = runOntogenShell("run " + model("piston.cell") + " --until 4 --frames 3 --interpret geometry,trace --format svg,obj --out " +
                          out.string() + " --stats");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  for (const char* name : {"piston_0000.svg", "piston_0001.obj", "piston_0002.txt"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  EXPECT_FALSE(fs::exists(out / "piston_0003.svg"));
  EXPECT_NE(result.out.find("cells 12"), std::string::npos) << result.out;
  std::string trace = readFile(out / "piston_0000.txt");
  EXPECT_EQ(trace, "piston\n");
}

TEST(Cli, SameSeedSameOutputDifferentSeedDifferent) {
  fs::path dir = scratch("seed");
  fs::path program = writeProgram(dir, "lsystem s {\n  axiom A\n  A -> A B : 0.5\n  A -> B A : 0.5\n}\n");
  std::string word = "word " + program.string() + " --at 12 --json";
  Result a = runOntogenShell(word + " --seed 3");
  Result b = runOntogenShell(word + " --seed 3");
  Result c = runOntogenShell(word + " --seed 4");
  ASSERT_EQ(a.exitCode, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_NE(a.out, c.out);
}

TEST(Cli, RunawayGrowthStopsWithTheLimitNamed) {
  fs::path dir = scratch("limit");
  fs::path program = writeProgram(dir, "lsystem s {\n  axiom A\n  A -> A A\n}\n");
  Result result = runOntogenShell("run " + program.string() + " --until 40 --max-cells 100000 --out " + (dir / "out").string());
  EXPECT_EQ(result.exitCode, 3);
  EXPECT_NE(result.err.find("past 100000 cells"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("--max-cells"), std::string::npos) << result.err;
}

TEST(Cli, DefineSetsAProgramsDefine) {
  Result result = runOntogenShell("word " + model("piston.cell") + " --at 1.04 --precision 3 --define WR=100");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  // The wheel radius moves the piston, the crank's arm and the flywheel; bend reads it too.
  EXPECT_EQ(result.out,
            "t = 1.04: (mov(100), 1) !(10) cC(60, 1) (bend(0.524), 1) !(2) cC(200, 1) (turn(2.09), 1) f(100) "
            "+(1.57) [ disc(0, 100) ]\n");
}

TEST(Cli, DefineRepeatsBeforeOrAfterTheFileAndTheLastValueWins) {
  Result result = runOntogenShell("word --define PR=20 --define WR=70 " + model("piston.cell") +
                          " --at 1.04 --precision 3 --define WR=100 --define PL=-5.5");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("(mov(100), 1) !(20) cC(-5.5, 1)"), std::string::npos) << result.out;
}

TEST(Cli, DefineOfAnUnknownNameListsTheDefinedOnesAndExitsWith2) {
  const std::string expected =
      "ontogen: error: cannot set 'SEGMENTS': the program has no #define SEGMENTS (it defines WR, KL, KR, PR, PL, ρ, "
      "E)\n";
  fs::path dir = scratch("define_unknown");
  const std::string file = model("piston.cell") + " --define SEGMENTS=3";
  for (const std::string& command :
       {"check " + file, "word " + file + " --at 1", "run " + file + " --out " + (dir / "out").string(),
        "timeline " + file + " --out " + (dir / "out.svg").string()}) {
    Result result = runOntogenShell(command);
    EXPECT_EQ(result.exitCode, 2) << command << "\n" << result.err;
    EXPECT_EQ(result.err, expected) << command;
    EXPECT_EQ(result.out, "") << command;
    EXPECT_FALSE(fs::exists(dir / "out")) << command;
    EXPECT_FALSE(fs::exists(dir / "out.svg")) << command;
  }
}

TEST(Cli, MalformedDefineExitsWith2) {
  Result noEquals = runOntogenShell("check " + model("piston.cell") + " --define WR");
  EXPECT_EQ(noEquals.exitCode, 2);
  EXPECT_EQ(noEquals.err, "ontogen: error: --define takes NAME=VALUE, as in --define WR=100, not 'WR'\n");
  Result noName = runOntogenShell("check " + model("piston.cell") + " --define =5");
  EXPECT_EQ(noName.exitCode, 2);
  EXPECT_NE(noName.err.find("--define takes NAME=VALUE"), std::string::npos) << noName.err;
  for (const char* value : {"abc", "", "1x", "pi", "nan", "inf", "1,5"}) {
    Result bad = runOntogenShell("check " + model("piston.cell") + " --define 'WR=" + value + "'");
    EXPECT_EQ(bad.exitCode, 2) << value;
    EXPECT_EQ(bad.err, std::string("ontogen: error: --define WR=") + value + ": '" + value +
                           "' is not a number (VALUE is a number such as 100, -2.5 or 1e-3)\n");
  }
  Result forms = runOntogenShell("check " + model("piston.cell") + " --define WR=+5 --define KL=1e3 --define E=.5");
  EXPECT_EQ(forms.exitCode, 0) << forms.err;
}

TEST(Cli, UnknownSystemIsABadCommandLine) {
  Result result = runOntogenShell("check " + model("piston.cell") + " --system wheel");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "ontogen: error: no system named 'wheel' (the program has: piston)\n");
}

TEST(Cli, UsageErrorsExitWith2) {
  EXPECT_EQ(runOntogenShell("run /no/such/file.cell").exitCode, 2);
  EXPECT_EQ(runOntogenShell("frobnicate").exitCode, 2);
  EXPECT_EQ(runOntogenShell("run " + model("koch.cell") + " --interpret nonsense --out /tmp/x").exitCode, 2);
}

TEST(Cli, HelpListsTheTables) {
  Result result = runOntogenShell("help");
  EXPECT_EQ(result.exitCode, 0);
  EXPECT_NE(result.out.find("besselj(n, x)"), std::string::npos);
  EXPECT_NE(result.out.find("--define NAME=VALUE"), std::string::npos);
  EXPECT_NE(result.out.find("cC(l, capped)"), std::string::npos);
  // Every set's table, the dynamics set's among them.
  const size_t dynamics = result.out.find("\nDynamics commands (set 'dynamics'");
  ASSERT_NE(dynamics, std::string::npos);
  EXPECT_NE(result.out.find("  wind(x, y, z[, gust, period])", dynamics), std::string::npos);
  EXPECT_NE(result.out.find("  servo(kp, kd[, torque])", dynamics), std::string::npos);
  // The keyword table (lang/keywords.h), before the directives.
  const size_t keywords = result.out.find("\nKeywords");
  ASSERT_NE(keywords, std::string::npos);
  EXPECT_LT(keywords, result.out.find("\nDirectives"));
  EXPECT_NE(result.out.find("  lsystem", keywords), std::string::npos);
  EXPECT_NE(result.out.find("  τ", keywords), std::string::npos);
}

TEST(Cli, TimelineWritesTheTimeStateDiagram) {
  fs::path out = scratch("timeline") / "anabaena.svg";
  Result result = runOntogenShell("timeline " + model("anabaena.cell") + " --until 4 --out " + out.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("19 cells over [0, 4]"), std::string::npos) << result.out;  // 1 + 2 + 3 + 5 + 8
  std::ifstream in(out);
  std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(runOntogenShell("timeline " + model("anabaena.cell") + " --out " + (scratch("timeline") / "a.txt").string())
                .exitCode,
            2);
}

// Paper 002's models on one thread and on all cores: the same JSON, byte for byte.
TEST(Cli, WordJsonIsTheSameOnOneThreadAndOnAll) {
  for (const char* name : {"heterocysts.cell", "colony.cell", "orchard.cell", "life.cell"}) {
    const std::string command = "word " + model(name) + " --at 3,12 --json --threads ";
    Result one = runOntogenShell(command + "1");
    Result all = runOntogenShell(command + "0");
    ASSERT_EQ(one.exitCode, 0) << name << ": " << one.err;
    ASSERT_EQ(all.exitCode, 0) << name << ": " << all.err;
    EXPECT_GT(one.out.size(), 200u) << name;
    EXPECT_EQ(one.out, all.out) << name;
  }
}
}  // namespace

namespace {

std::string program(const std::string& name) { return std::string(ONTOGEN_SOURCE_DIR) + "/tests/programs/" + name; }

}  // namespace

TEST(Cli, DeclaredCellNamedInAnLsystemIsDrawnThroughItsInterpretBlock) {
  fs::path out = scratch("cell_in_lsystem");
  Result result = runOntogenShell("run " + program("cell_in_lsystem.cell") + " --format obj --out " + out.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  std::string obj = readFile(out / "cell_in_lsystem.obj");
  // X(3) draws F(3) through its block, then F(1): one chain of two lines up to y = 4.
  EXPECT_NE(obj.find("v 0 3 0\nv 0 4 0\n"), std::string::npos) << obj;
  EXPECT_NE(obj.find("l 1 2\nl 2 3\n"), std::string::npos) << obj;
}

TEST(Cli, RunWritesGlbAndPngByDefaultAndRejectsUnknownFormats) {
  fs::path out = scratch("default_formats");
  Result result = runOntogenShell("run " + model("horn_gc.cell") + " --size 64x48 --out " + out.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_TRUE(fs::exists(out / "horn_gc.glb"));
  EXPECT_TRUE(fs::exists(out / "horn_gc.png"));
  Result bad = runOntogenShell("run " + model("horn_gc.cell") + " --format glb,gltf --out " + out.string());
  EXPECT_EQ(bad.exitCode, 2) << bad.err;
  EXPECT_NE(bad.err.find("unknown format 'gltf'"), std::string::npos) << bad.err;
  Result size = runOntogenShell("run " + model("horn_gc.cell") + " --size big --out " + out.string());
  EXPECT_NE(size.exitCode, 0);
  EXPECT_NE(size.err.find("WIDTHxHEIGHT"), std::string::npos) << size.err;
}

// --speed and --fps time the movie, --look colours the pictures: Koch's 4 s of growth at
// 2 s a second and 10 frames a second are 21 frames (ffprobe), and the dark look's
// background is the picture's corner (ffmpeg decodes it).
TEST(Cli, SpeedFpsAndLookReachTheMovieAndThePicture) {
  ONTOGEN_REQUIRE_CHECKER(std::system("command -v ffprobe >/dev/null 2>&1") == 0, "ffmpeg not installed");
  fs::path out = scratch("speed_fps_look");
  Result result = runOntogenShell("run " + model("koch.cell") + " --format mp4,png --speed 2 --fps 10 --size 32x32 --look dark --out " +
                          out.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                            "-of csv=p=0 '" + (out / "koch.mp4").string() + "' > '" + (out / "frames.txt").string() + "'";
  ASSERT_EQ(std::system(probe.c_str()), 0);
  EXPECT_EQ(std::stoi(readFile(out / "frames.txt")), 21);
  const std::string decode = "ffmpeg -v error -i '" + (out / "koch.png").string() + "' -f rawvideo -pix_fmt rgb24 '" +
                             (out / "koch.rgb").string() + "'";
  ASSERT_EQ(std::system(decode.c_str()), 0);
  const std::string rgb = readFile(out / "koch.rgb");
  ASSERT_EQ(rgb.size(), 32u * 32 * 3);
  EXPECT_EQ(static_cast<uint8_t>(rgb[0]), 28);
  EXPECT_EQ(static_cast<uint8_t>(rgb[1]), 30);
  EXPECT_EQ(static_cast<uint8_t>(rgb[2]), 34);
}

// --up z turns the OBJ and the PLY (binary by default) into z-up files: every vertex
// of the OBJ is the y-up one turned a quarter about x.
TEST(Cli, UpZWritesZUpObjAndBinaryPly) {
  fs::path out = scratch("up_z");
  Result result = runOntogenShell("run " + model("cube.cell") + " --format obj,ply --up z --out " + out.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::string ply = readFile(out / "cube.ply");
  EXPECT_EQ(ply.rfind("ply\nformat binary_little_endian 1.0\ncomment ontogen geometry, z up\n", 0), 0u) << ply.substr(0, 80);
  const std::string obj = readFile(out / "cube.obj");
  EXPECT_EQ(obj.rfind("# ontogen geometry, z up\n", 0), 0u) << obj.substr(0, 80);
  Result plain = runOntogenShell("run " + model("cube.cell") + " --format obj --out " + (out / "y").string());
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  // The same vertices, turned: (x, y, z) -> (x, -z, y).
  auto vertices = [](const std::string& text) {
    std::vector<std::array<double, 3>> list;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      std::array<double, 3> v{};
      if (std::sscanf(line.c_str(), "v %lf %lf %lf", &v[0], &v[1], &v[2]) == 3) list.push_back(v);
    }
    return list;
  };
  const auto z = vertices(obj), y = vertices(readFile(out / "y" / "cube.obj"));
  ASSERT_EQ(z.size(), y.size());
  ASSERT_FALSE(z.empty());
  for (std::size_t i = 0; i < z.size(); ++i) {
    EXPECT_EQ(z[i][0], y[i][0]);
    EXPECT_EQ(z[i][1], y[i][2] == 0 ? 0 : -y[i][2]);
    EXPECT_EQ(z[i][2], y[i][1]);
  }
}

TEST(Cli, GeometryModelsRunAndWriteValidOutputs) {
  const fs::path modules = fs::path(ONTOGEN_SOURCE_DIR) / ".tools" / "node_modules";
  const bool validator = fs::exists(modules / "gltf-validator" / "package.json");
  for (const char* name : {"horn_cylinders", "horn_gc", "cube", "replicator", "plant_ceiling", "flower", "piston",
                           "triangles", "triangles_attracted"}) {
    fs::path out = scratch(std::string("model_") + name);
    Result result = runOntogenShell("run " + model(std::string(name) + ".cell") + " --frames 3 --size 96x96 --format glb,png,obj --out " +
                            out.string());
    ASSERT_EQ(result.exitCode, 0) << name << ": " << result.err;
    EXPECT_TRUE(fs::exists(out / (std::string(name) + ".png"))) << name;
    EXPECT_TRUE(fs::exists(out / (std::string(name) + "_0002.obj"))) << name;
    const fs::path glb = out / (std::string(name) + ".glb");
    ASSERT_TRUE(fs::exists(glb)) << name;
    if (!validator) continue;
    const std::string script = std::string(ONTOGEN_SOURCE_DIR) + "/tests/interpreters/validate_gltf.js";
    const std::string command = "node '" + script + "' '" + modules.string() + "' '" + glb.string() + "' > '" +
                                (out / "report.txt").string() + "' 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << name << ": " << readFile(out / "report.txt");
  }
  ONTOGEN_REQUIRE_CHECKER(validator, "gltf-validator not installed (bash .ci/setup installs it)");
}

namespace {

TEST(Cli, SurfaceFilesLoadRelativeToTheProgramAndBadOnesStopTheRun) {
  fs::path dir = scratch("surfaces");
  fs::create_directories(dir / "shapes");
  std::ofstream(dir / "shapes" / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  writeProgram(dir, "#surface 2 \"shapes/tri.obj\"\nlsystem s {\n  #until 1\n  axiom Leaf\n}\ncell Leaf {\n"
                    "  interpret geometry { surface(2, 4) blend(1, 2, 0.5, 2, 0.5) }\n}\n");
  Result good = runOntogenShell("run " + (dir / "program.cell").string() + " --format obj --out " + (dir / "out").string());
  ASSERT_EQ(good.exitCode, 0) << good.err;
  const std::string obj = readFile(dir / "out" / "program.obj");
  EXPECT_NE(obj.find("v 4 0 0"), std::string::npos) << obj;  // scaled by 4
  EXPECT_NE(obj.find("v 0 4 0"), std::string::npos) << obj;

  writeProgram(dir, "#surface 2 \"shapes/none.obj\"\nlsystem s {\n  #until 1\n  axiom Leaf\n}\ncell Leaf {\n"
                    "  interpret geometry { surface(2) }\n}\n");
  // A file the run could not use is the program's error, found by check as by run.
  Result missing = runOntogenShell("run " + (dir / "program.cell").string() + " --format obj --out " + (dir / "bad").string());
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("program.cell:1:1: error: cannot read surface " + (dir / "shapes" / "none.obj").string()),
            std::string::npos)
      << missing.err;
  EXPECT_FALSE(fs::exists(dir / "bad" / "program.obj"));
  EXPECT_EQ(runOntogenShell("check " + (dir / "program.cell").string()).exitCode, 1);
  std::ofstream(dir / "shapes" / "points.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  writeProgram(dir, "lsystem s {\n  #surface 3 \"shapes/points.obj\"\n  axiom Leaf\n}\n");
  Result faceless = runOntogenShell("check " + (dir / "program.cell").string());
  EXPECT_EQ(faceless.exitCode, 1);
  EXPECT_NE(faceless.err.find("program.cell:2:3: error: " + (dir / "shapes" / "points.obj").string() +
                              ": no faces (an OBJ surface needs 'f' lines)"),
            std::string::npos)
      << faceless.err;

  writeProgram(dir, "lsystem s {\n  #until 1\n  axiom Leaf\n}\ncell Leaf {\n  interpret geometry { surface(5) }\n}\n");
  Result undefined = runOntogenShell("run " + (dir / "program.cell").string() + " --format obj --out " + (dir / "bad").string());
  EXPECT_EQ(undefined.exitCode, 3);
  EXPECT_NE(undefined.err.find("surface 5 is not defined"), std::string::npos) << undefined.err;
  EXPECT_FALSE(fs::exists(dir / "bad" / "program.obj"));

  writeProgram(dir, "#surface 1.5 \"shapes/tri.obj\"\nlsystem s { axiom A }\n");
  Result number = runOntogenShell("check " + (dir / "program.cell").string());
  EXPECT_EQ(number.exitCode, 1);
  EXPECT_NE(number.err.find("program.cell:1:1: error: #surface takes a whole number 0 to 1023"), std::string::npos)
      << number.err;
  writeProgram(dir, "#surface 1\nlsystem s { axiom A }\n");
  Result file = runOntogenShell("check " + (dir / "program.cell").string());
  EXPECT_EQ(file.exitCode, 1);
  EXPECT_NE(file.err.find("program.cell:1:1: error: expected the OBJ file in double quotes after the surface number"),
            std::string::npos)
      << file.err;
}

// Every cell of `word --json` has its stable id and the id of the cell it hangs from:
// ABOP's axial tree in a bracketed word, the system cell above a nested pool, -1 for none;
// a joint rewritten with `=X` keeps its id from one time to the next.
TEST(Cli, WordJsonGivesIdsAndParents) {
  fs::path dir = scratch("ids");
  fs::path program = writeProgram(dir, "system leaf { pool linear; axiom L; }\ncell L { }\n"
                                       "lsystem t {\n  axiom F(1) [ + F(2) ] F(3) (sw, 0) leaf\n"
                                       "  (sw, 1) -> =(su, 0)\n}\n");
  Result result = runOntogenShell("word " + program.string() + " --at 0,1.5 --json --system t");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  nlohmann::json word = nlohmann::json::parse(result.out);
  const auto& cells = word["times"][0]["cells"];
  ASSERT_EQ(cells.size(), 8u);
  EXPECT_EQ(cells[0]["parent"], -1);
  const auto f1 = cells[0]["id"];
  EXPECT_EQ(cells[3]["label"], "F");
  EXPECT_EQ(cells[3]["parent"], f1) << "F(2) hangs from F(1)";
  EXPECT_EQ(cells[5]["parent"], f1) << "F(3) hangs from F(1)";
  EXPECT_EQ(cells[6]["parent"], cells[5]["id"]) << "sw hangs from F(3)";
  const auto& system = cells[7];
  ASSERT_EQ(system["pool"].size(), 1u);
  EXPECT_EQ(system["pool"][0]["parent"], system["id"]) << "a nested pool hangs from its system cell";
  const auto& later = word["times"][1]["cells"];
  EXPECT_EQ(later[6]["label"], "su");
  EXPECT_EQ(later[6]["id"], cells[6]["id"]) << "=su keeps sw's identity";
  EXPECT_EQ(later[0]["id"], f1) << "ids are stable while a cell lives";
}

// `word --interpreted` prints the homomorphism's image; without it, the developing word.
TEST(Cli, WordInterpretedPrintsTheHomomorphismsImage) {
  fs::path dir = scratch("interpreted");
  fs::path program = writeProgram(dir, "lsystem t {\n  axiom A\n  A -> A N\n  homomorphism:\n  N -> F\n}\n");
  Result image = runOntogenShell("word " + program.string() + " --at 0,2 --interpreted");
  ASSERT_EQ(image.exitCode, 0) << image.err;
  EXPECT_EQ(image.out, "t = 0: A\nt = 2: A F F\n");
  Result word = runOntogenShell("word " + program.string() + " --at 2");
  ASSERT_EQ(word.exitCode, 0) << word.err;
  EXPECT_EQ(word.out, "t = 2: A N N\n");
}

// `ontogen help` prints the directive table: a line per directive under the settings it
// belongs to. The directives are those docs/LANGUAGE.md section 3.2 lists, which
// tests/lang/directives_test.cpp holds to the table itself.
TEST(Cli, HelpListsEveryDirective) {
  std::ifstream doc(std::string(ONTOGEN_SOURCE_DIR) + "/docs/LANGUAGE.md");
  std::string line, section;
  for (bool in = false; std::getline(doc, line);) {
    if (line.rfind("### ", 0) == 0) in = line.rfind("### 3.2 ", 0) == 0;
    if (in && line.rfind("| `#", 0) == 0) section += line.substr(0, line.find('|', 1)) + "\n";
  }
  std::set<std::string> documented;
  // The names after each "`#" (no <regex>: GCC 12 warns falsely inside it under the sanitizers).
  for (size_t at = section.find("`#"); at != std::string::npos; at = section.find("`#", at + 1)) {
    size_t stop = at + 2;
    while (stop < section.size() && section[stop] >= 'a' && section[stop] <= 'z') ++stop;
    if (stop > at + 2) documented.insert(section.substr(at + 2, stop - at - 2));
  }
  ASSERT_GE(documented.size(), 17u) << section;

  Result result = runOntogenShell("help");
  ASSERT_EQ(result.exitCode, 0);
  const size_t start = result.out.find("\nDirectives");
  ASSERT_NE(start, std::string::npos) << result.out;
  std::istringstream lines(result.out.substr(start + 1));
  std::set<std::string> listed, owners;
  while (std::getline(lines, line) && !line.empty()) {  // the section ends at a blank line
    if (line.rfind("    #", 0) == 0) {
      EXPECT_TRUE(listed.insert(line.substr(5, line.find_first_of(" /", 5) - 5)).second) << line;
      EXPECT_GT(line.size(), 60u) << "kind, values and doc: " << line;
    } else if (line.rfind("  ", 0) == 0) {
      owners.insert(line.substr(2));
    }
  }
  EXPECT_EQ(listed, documented);
  EXPECT_EQ(owners, (std::set<std::string>{"constants", "world", "geometry", "music", "notation"}));
}

// `ontogen help --reference` prints docs/COMMANDS.md as committed (the reference's own
// test holds the file to the tables).
TEST(Cli, HelpReferencePrintsTheCommittedCommandReference) {
  Result result = runOntogenShell("help --reference");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/docs/COMMANDS.md", std::ios::binary);
  const std::string committed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(result.out, committed);
}

}  // namespace
