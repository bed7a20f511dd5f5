// The run as a library object (interpreters/run.h): the schedule of frames, the files
// written, the report's diagnostics with their cells, spans and times.

#include <gtest/gtest.h>

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "interpreters/run.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;

fs::path scratchDir(const std::string& name) { return fs::path(ONTOGEN_BINARY_DIR) / "run_test" / name; }

fs::path scratch(const std::string& name) {
  fs::path dir = scratchDir(name);
  fs::remove_all(dir);
  return dir;
}

TEST(Run, GrowsTheFramesAndReportsTheFilesAndStats) {
  RunDef def;
  def.program = testing_support::compileModel("piston.cell");
  def.stem = "piston";
  def.until = 4;
  def.frames = 5;
  def.setOptions.formats = "obj,glb";
  def.out = scratch("piston");
  int calls = 0;
  def.progress = [&](int done, int total) {
    ++calls;
    EXPECT_EQ(total, 5);
    EXPECT_EQ(done, calls);
  };
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  ASSERT_TRUE(report.ok()) << (report.diagnostics.empty() ? "" : report.diagnostics[0].message);
  EXPECT_EQ(calls, 5);
  EXPECT_DOUBLE_EQ(report.time, 4);
  EXPECT_EQ(report.stats.steps, 4u * 25) << "steps of the program's #dt 0.04";
  ASSERT_EQ(report.files.size(), 5u * 2 + 1) << "an OBJ and its MTL per frame, one glb";
  for (const fs::path& file : report.files) EXPECT_TRUE(fs::exists(file)) << file;
  ASSERT_NE(run.world(), nullptr);
  EXPECT_EQ(report.cells, run.world()->totalCells());
}

TEST(Run, AModelErrorIsADiagnosticWithItsCellSpanAndTime) {
  RunDef def;
  def.program = testing_support::compileOrFail(
      "cell A { rules { age > 1.5 : -> (B, 2); } }\ncell B { lifetime 1; }\nsystem s { pool linear; axiom A; }",
      "born_too_old.cell");
  def.until = 5;
  def.sets = {"trace"};
  def.out = scratch("model_error");
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  EXPECT_EQ(report.status, RunStatus::ModelFailed);
  ASSERT_EQ(report.diagnostics.size(), 1u);
  const RunDiagnostic& error = report.diagnostics[0];
  EXPECT_EQ(error.severity, Severity::Error);
  EXPECT_EQ(error.cell, "A");
  ASSERT_TRUE(error.time.has_value());
  EXPECT_DOUBLE_EQ(*error.time, 2);
  ASSERT_TRUE(error.span.valid());
  EXPECT_EQ(formatRunDiagnostic(error).rfind("born_too_old.cell:1:33: error: 'B' would be born with age 2", 0), 0u)
      << formatRunDiagnostic(error);
}

TEST(Run, TurtleWarningsReachTheReportWithTheirPlaceCountedOverTheRun) {
  RunDef def;
  def.program = testing_support::compileOrFail(
      "lsystem l {\n  axiom A\n  interpret geometry A { F(1) ] ] }\n  A -> A\n}", "pops.cell");
  def.until = 3;
  def.frames = 3;
  def.setOptions.formats = "obj";
  def.out = scratch("warnings");
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  ASSERT_TRUE(report.ok());
  ASSERT_EQ(report.diagnostics.size(), 1u);
  const RunDiagnostic& warning = report.diagnostics[0];
  EXPECT_EQ(warning.severity, Severity::Warning);
  EXPECT_EQ(warning.count, 6u) << "two in each of three frames";
  EXPECT_EQ(warning.cell, "A");
  EXPECT_EQ(formatRunDiagnostic(warning).rfind("pops.cell:3:31: warning: the turtle ignored 6 unmatched ']'", 0), 0u)
      << formatRunDiagnostic(warning);
}

TEST(Run, ABadDefinitionGrowsNothing) {
  RunDef def;
  def.program = testing_support::compileModel("koch.cell");
  def.sets = {"geometry", "sculpture"};
  def.out = scratch("bad");
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  EXPECT_EQ(report.status, RunStatus::BadDefinition);
  ASSERT_EQ(report.diagnostics.size(), 1u);
  EXPECT_NE(report.diagnostics[0].message.find("unknown interpretation set 'sculpture'"), std::string::npos);
  EXPECT_EQ(run.world(), nullptr);
  EXPECT_FALSE(fs::exists(scratch("bad")));
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

RunReport runWithMemoryLimit(const std::string& name, uint64_t mebibytes, const std::string& formats, int frames,
                             int size = 800) {
  RunDef def;
  def.program = testing_support::compileModel("piston.cell");
  def.until = 1;
  def.frames = frames;
  def.setOptions.formats = formats;
  def.setOptions.render.width = def.setOptions.render.height = size;
  def.world.limits.maxMemoryBytes = mebibytes << 20;
  def.out = scratch(name);
  ontogen::Run run(std::move(def));
  return run.execute();
}

// A picture's buffers are not in a pool, but they count against the memory limit.
TEST(Run, APictureLargerThanTheMemoryLimitStopsTheRunWithTheLimitNamed) {
  const RunReport report = runWithMemoryLimit("big_picture", 100, "png", 1, 8192);
  EXPECT_EQ(report.status, RunStatus::ModelFailed);
  ASSERT_FALSE(report.diagnostics.empty());
  EXPECT_EQ(report.diagnostics[0].message,
            "a 8192x8192 picture needs about 3553 MiB, past the memory limit of 100 MiB; raise it with --max-memory MIB");
  EXPECT_TRUE(runWithMemoryLimit("small_picture", 100, "png", 1, 800).ok());
}

// Every frame of a .glb is held until the last is written: they count as they come.
TEST(Run, TheFramesAGlbHoldsCountAgainstTheMemoryLimit) {
  // The piston's three parts are written once and each frame holds their places (about
  // 250 bytes): 6000 frames pass 1 MiB.
  const RunReport report = runWithMemoryLimit("many_frames", 1, "glb", 6000);
  EXPECT_EQ(report.status, RunStatus::ModelFailed);
  ASSERT_FALSE(report.diagnostics.empty());
  EXPECT_NE(report.diagnostics[0].message.find("the .glb's "), std::string::npos) << report.diagnostics[0].message;
  EXPECT_NE(report.diagnostics[0].message.find("--max-memory"), std::string::npos);
  EXPECT_TRUE(runWithMemoryLimit("few_frames", 64, "glb", 400).ok());
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// The programs stay alive while their diagnostics' spans are read.
std::vector<std::shared_ptr<const Program>> keptPrograms;

RunDiagnostic firstErrorOf(const std::string& text, const std::string& name, const std::string& set) {
  RunDef def;
  def.program = testing_support::compileOrFail(text, name);
  keptPrograms.push_back(def.program);
  def.until = 2;
  def.sets = {set};
  def.setOptions.formats = "obj";
  def.out = scratch("instruction_" + set);
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  EXPECT_EQ(report.status, RunStatus::ModelFailed) << name;
  for (const RunDiagnostic& diagnostic : report.diagnostics)
    if (diagnostic.severity == Severity::Error) return diagnostic;
  ADD_FAILURE() << "no error for " << name;
  return {};
}

// An instruction's argument outside what its set can carry out is the program's error at
// the instruction, with its cell and time: exit code 3, not an output error.
TEST(Run, InstructionArgumentsOutOfRangeAreLocatedModelErrors) {
  const RunDiagnostic pixel = firstErrorOf(
      "cell C { interpret image { pixel(-5, -5, 1) } }\nsystem g { pool grid(4, 4) wrap moore; fill C; }\n", "px.cell",
      "image");
  EXPECT_EQ(pixel.cell, "C");
  EXPECT_EQ(pixel.time, 2);
  EXPECT_EQ(formatRunDiagnostic(pixel),
            "px.cell:1:28: error: pixel(-5, -5) is outside the picture: a site's coordinates are whole numbers 0 to "
            "8191 (in the interpretation of 'C' at t = 2)\n"
            "cell C { interpret image { pixel(-5, -5, 1) } }\n"
            "                           ^~~~~~~~~~~~~~~~\n");

  const RunDiagnostic note =
      firstErrorOf("lsystem m {\n  axiom A\n  interpret music A { note(1e308, 60) }\n  A -> A\n}\n", "note.cell", "music");
  EXPECT_EQ(note.cell, "A");
  EXPECT_EQ(formatRunDiagnostic(note).rfind("note.cell:3:23: error: the note would end at beat 1e+308, past beat "
                                            "559240, the end of any MIDI file at this resolution (#ppq) (in the "
                                            "interpretation of 'A' at t = 2)\n",
                                            0),
            0u)
      << formatRunDiagnostic(note);

  const RunDiagnostic at =
      firstErrorOf("lsystem m {\n  axiom A\n  interpret music A { at(1e9) note() }\n  A -> A\n}\n", "at.cell", "music");
  EXPECT_NE(at.message.find("the time would move to beat 1e+09"), std::string::npos) << at.message;
  EXPECT_TRUE(at.span.valid());

  const RunDiagnostic surface = firstErrorOf(
      "lsystem s {\n  axiom A\n  interpret geometry A { F(1) surface(4) }\n  A -> A\n}\n", "surface.cell", "geometry");
  EXPECT_EQ(formatRunDiagnostic(surface).rfind("surface.cell:3:31: error: surface 4 is not defined", 0), 0u)
      << formatRunDiagnostic(surface);
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

std::string fileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The words of a text file that are no finite number but read as one (inf, nan, ...).
std::vector<std::string> nonFiniteWords(const std::string& text) {
  std::vector<std::string> found;
  std::string word;
  std::istringstream in(text);
  while (in >> word) {
    for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* bad : {"inf", "nan"})
      if (word.find(bad) != std::string::npos && word.find("mtl") == std::string::npos) found.push_back(word);
  }
  return found;
}

// The glTF JSON chunk of a .glb.
nlohmann::json glbJson(const fs::path& path) {
  const std::string bytes = fileText(path);
  if (bytes.size() < 20) return {};
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

// Coordinates past what any output holds are left out of every file, and the run says so
// at the instruction that drew them.
TEST(Run, NoOutputHoldsANonFiniteNumberAndTheRunSaysWhatItLeftOut) {
  RunDef def;
  def.program = testing_support::compileOrFail(
      "lsystem a {\n  axiom F(1) F(1e308) F(1e308) + F(1)\n  F(x) -> F(x)\n  interpret geometry F(x) { !(0.1) F(x) }\n}\n",
      "huge.cell");
  keptPrograms.push_back(def.program);
  def.stem = "huge";
  def.until = 1;
  def.setOptions.formats = "glb,obj,ply,svg,png";
  def.out = scratch("non_finite");
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  ASSERT_TRUE(report.ok()) << (report.diagnostics.empty() ? "" : report.diagnostics[0].message);
  for (const char* name : {"huge.obj", "huge.ply", "huge.svg"}) {
    const std::string text = fileText(scratchDir("non_finite") / name);
    EXPECT_FALSE(text.empty()) << name;
    EXPECT_EQ(nonFiniteWords(text), std::vector<std::string>{}) << name;
  }
  // The first F(1) is drawn: a cylinder of 12 sides from 0 to 1.
  EXPECT_NE(fileText(scratchDir("non_finite") / "huge.obj").find("# 24 vertices"), std::string::npos);
  const nlohmann::json gltf = glbJson(scratchDir("non_finite") / "huge.glb");
  ASSERT_TRUE(gltf.contains("accessors"));
  for (const auto& accessor : gltf["accessors"]) {
    for (const char* bound : {"min", "max"}) {
      if (!accessor.contains(bound)) continue;
      for (const auto& value : accessor[bound]) EXPECT_TRUE(value.is_number()) << accessor.dump();
    }
  }
  int warned = 0;
  for (const RunDiagnostic& diagnostic : report.diagnostics) {
    if (diagnostic.message.find("left out 3 shapes with coordinates not finite or beyond ±1e30") == std::string::npos)
      continue;
    ++warned;
    EXPECT_EQ(diagnostic.severity, Severity::Warning);
    EXPECT_EQ(diagnostic.cell, "F");
    EXPECT_EQ(formatRunDiagnostic(diagnostic).rfind("huge.cell:4:36: warning:", 0), 0u) << formatRunDiagnostic(diagnostic);
  }
  EXPECT_EQ(warned, 1);
}

// A frame with nothing to draw: a readable .obj (one point), no .ply (it holds faces
// only), and a warning for each.
TEST(Run, AFrameWithNothingToDrawWarnsAndWritesNoUnreadableFile) {
  RunDef def;
  def.program = testing_support::compileOrFail("lsystem a {\n  axiom A\n  A -> A\n}\n", "nothing.cell");
  def.stem = "nothing";
  def.until = 1;
  def.setOptions.formats = "obj,ply";
  def.out = scratch("nothing");
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  ASSERT_TRUE(report.ok());
  EXPECT_TRUE(fs::exists(scratchDir("nothing") / "nothing.obj"));
  EXPECT_FALSE(fs::exists(scratchDir("nothing") / "nothing.ply"));
  std::vector<std::string> warnings;
  for (const RunDiagnostic& diagnostic : report.diagnostics)
    if (diagnostic.severity == Severity::Warning) warnings.push_back(diagnostic.message);
  EXPECT_EQ(warnings, (std::vector<std::string>{
                          "1 frame (the first at t = 1) had nothing to draw: its .obj holds one point at the origin, "
                          "as readers refuse one without a mesh",
                          "1 frame (the first at t = 1) had no surface: no .ply was written for it, as readers refuse "
                          "one without a face"}));
}

}  // namespace
}  // namespace ontogen
