// The studio without a browser: the model re-grown as its file and defines change, the
// routes the page uses, who may ask them over a real socket. The HTTP server alone is
// tests/studio/http_server_test.cpp, the gallery tests/studio/gallery_test.cpp.

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lang/compiler.h"
#include "lang/convert/convert.h"
#include "studio/gallery.h"
#include "studio/http_server.h"
#include "studio/studio_assets.h"
#include "studio/studio_model.h"
#include "studio/studio_server.h"
#include "tests/studio/socket_client.h"
#include "tests/studio/studio_fixture.h"

namespace ontogen::studio {
namespace {

namespace fs = std::filesystem;

using test::exchange;
using test::kTree;
using test::StudioFixture;

TEST_F(StudioFixture, ModelGrowsFollowsItsFileAndKeepsTheLastGoodModel) {
  StudioModel model(modelDef());
  model.regrow();
  ASSERT_EQ(model.modelVersion(), 1u) << model.state().dump(2);
  EXPECT_TRUE(model.glb().starts_with("glTF"));
  const nlohmann::json state = model.state();
  EXPECT_TRUE(state["ok"].get<bool>());
  // At 3 s: 8 apices A, 7 F, 6 brackets and turns around each of the 7 branchings, and !.
  EXPECT_EQ(state["cells"], 8 + 7 + 7 * 6 + 1);
  ASSERT_EQ(state["defines"].size(), 2u);
  EXPECT_EQ(state["defines"][0]["name"], "ANGLE");
  EXPECT_EQ(state["defines"][0]["low"], 1.0);  // a whole number of 1 or more stays at least 1
  EXPECT_EQ(state["defines"][0]["high"], 60.0);
  EXPECT_EQ(state["defines"][1]["line"], 2);
  EXPECT_FALSE(model.refresh());  // nothing changed

  const std::string firstGlb = model.glb();
  EXPECT_THROW(model.setDefine("NOPE", 1), std::invalid_argument);
  // LEN's slider spans [0, 2] (twice the written value): past it is refused.
  EXPECT_EQ(state["defines"][1]["high"], 2.0);
  EXPECT_THROW(model.setDefine("LEN", 2.5), std::invalid_argument);
  EXPECT_THROW(model.setDefine("LEN", -1), std::invalid_argument);
  EXPECT_EQ(model.version(), 1u);
  model.setDefine("LEN", 2);
  model.regrow();
  EXPECT_EQ(model.modelVersion(), 2u);
  EXPECT_NE(model.glb(), firstGlb);
  EXPECT_EQ(model.defineValues().at("LEN"), 2.0);

  // From here the model grows on its own thread.
  model.start();
  write(std::string(kTree) + "oops ->\n");
  EXPECT_TRUE(model.refresh());
  ASSERT_TRUE(model.waitIdle());
  EXPECT_EQ(model.version(), 3u);
  EXPECT_EQ(model.modelVersion(), 2u);  // the last model that grew stays
  const nlohmann::json broken = model.state();
  EXPECT_FALSE(broken["ok"].get<bool>());
  ASSERT_FALSE(broken["diagnostics"].empty());
  EXPECT_EQ(broken["diagnostics"][0]["line"], 8);
  EXPECT_NE(broken["diagnostics"][0]["text"].get<std::string>().find("tree.cell:8:"), std::string::npos);
  EXPECT_EQ(broken["defines"][1]["value"], 2.0);  // the slider keeps its value

  write(kTree);
  EXPECT_TRUE(model.refresh());
  ASSERT_TRUE(model.waitIdle());
  EXPECT_EQ(model.modelVersion(), 3u);
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The file is the source of truth (README, "The studio"): a slider's value is marked as
// overriding the file's number until it is written into the file or dropped, and an edit
// of the define in the file wins over a slider moved before it.
TEST_F(StudioFixture, ASlidersValueOverridesTheFileVisiblyUntilWrittenOrDropped) {
  StudioModel model(modelDef());
  model.regrow();
  auto define = [&](const char* name) {
    const nlohmann::json state = model.state();
    for (const nlohmann::json& d : state["defines"])
      if (d["name"] == name) return d;
    return nlohmann::json();
  };
  EXPECT_FALSE(define("LEN")["overridden"].get<bool>());
  EXPECT_THROW(model.writeDefine("LEN"), std::invalid_argument);  // nothing of the page's to write
  EXPECT_THROW(model.dropDefine("LEN"), std::invalid_argument);

  // Moved: the page's value is in effect and marked at once, before the growth.
  model.setDefine("LEN", 1.75);
  EXPECT_TRUE(define("LEN")["overridden"].get<bool>());
  EXPECT_EQ(define("LEN")["value"], 1.75);
  EXPECT_EQ(define("LEN")["written"], 1.0);
  model.regrow();
  const std::string longer = model.glb();
  // Dropped: the file's number again.
  model.dropDefine("LEN");
  EXPECT_FALSE(define("LEN")["overridden"].get<bool>());
  EXPECT_EQ(define("LEN")["value"], 1.0);
  model.regrow();
  EXPECT_NE(model.glb(), longer);

  // Written: the file says 1.75 where it said 1, and nothing else of it changes.
  model.setDefine("LEN", 1.75);
  model.regrow();
  EXPECT_EQ(model.writeDefine("LEN"), file.string());
  std::string expected = kTree;
  expected.replace(expected.find("LEN 1"), 5, "LEN 1.75");
  EXPECT_EQ(readText(file), expected);
  EXPECT_FALSE(define("LEN")["overridden"].get<bool>());
  model.regrow();
  EXPECT_EQ(define("LEN")["written"], 1.75);
  EXPECT_EQ(model.glb(), longer);  // the same model, now from the file alone

  // An edit of the file's ANGLE wins over the ANGLE slider; LEN's slider, whose number the
  // edit left alone, stays.
  model.setDefine("ANGLE", 45);
  model.setDefine("LEN", 0.5);
  model.regrow();
  std::string edited = expected;
  edited.replace(edited.find("ANGLE 30"), 8, "ANGLE 20");
  write(edited);
  model.regrow();
  EXPECT_EQ(define("ANGLE")["value"], 20.0);
  EXPECT_FALSE(define("ANGLE")["overridden"].get<bool>());
  EXPECT_EQ(define("LEN")["value"], 0.5);
  EXPECT_TRUE(define("LEN")["overridden"].get<bool>());
  // A file changed since it was read is not written over: that edit would be lost.
  write(edited + "// more\n");
  EXPECT_THROW(model.writeDefine("LEN"), std::invalid_argument);
  EXPECT_EQ(readText(file), edited + "// more\n");
  EXPECT_FALSE(fs::exists(file.string() + ".ontogen-studio-write"));
}

// Every file the program reads is watched: an import (at any depth) and a #surface file
// grow the model again when they change, and an import's error names the import, at its
// own line, not the program's line of that number.
TEST_F(StudioFixture, ImportsAndSurfacesAreWatchedAndAnImportsErrorNamesItsFile) {
  const fs::path lib = folder / "lib.cell";
  const fs::path shape = folder / "shapes" / "tri.obj";
  fs::create_directories(shape.parent_path());
  auto rewrite = [&](const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(++rewrites));
  };
  rewrite(lib, "#define TURN 30\n");
  rewrite(shape, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("import \"lib.cell\";\n#surface 2 \"shapes/tri.obj\"\nlsystem s {\n  #until 1\n"
        "  axiom F(1) +(TURN) F(1) Leaf\n}\ncell Leaf {\n  interpret geometry { surface(2, 4) }\n}\n");
  StudioModel model(modelDef());
  model.regrow();
  ASSERT_EQ(model.modelVersion(), 1u) << model.state().dump(2);
  EXPECT_EQ(model.watchedFiles(), (std::vector<std::string>{lib.string(), shape.string()}));
  EXPECT_FALSE(model.refresh());
  std::string last = model.glb();

  rewrite(lib, "#define TURN 60\n");
  EXPECT_TRUE(model.refresh());
  model.regrow();
  ASSERT_EQ(model.modelVersion(), 2u) << model.state().dump(2);
  EXPECT_NE(model.glb(), last);
  last = model.glb();
  EXPECT_FALSE(model.refresh());

  rewrite(shape, "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n");
  EXPECT_TRUE(model.refresh());
  model.regrow();
  ASSERT_EQ(model.modelVersion(), 3u) << model.state().dump(2);
  EXPECT_NE(model.glb(), last);

  // The import broken at its line 2: the diagnostic is the import's.
  rewrite(lib, "#define TURN 60\n#define BAD 1 + * 2\n");
  EXPECT_TRUE(model.refresh());
  model.regrow();
  const nlohmann::json state = model.state();
  EXPECT_FALSE(state["ok"].get<bool>());
  EXPECT_EQ(state["sourceName"], file.string());
  ASSERT_FALSE(state["diagnostics"].empty());
  const nlohmann::json& error = state["diagnostics"][0];
  EXPECT_EQ(error["file"], lib.string()) << state["diagnostics"].dump(2);
  EXPECT_EQ(error["line"], 2);
  EXPECT_TRUE(error["text"].get<std::string>().starts_with(lib.string() + ":2:")) << error["text"];
  EXPECT_EQ(model.modelVersion(), 3u);
  // Still watched while the program does not compile, the surface too; mended, it grows.
  EXPECT_EQ(model.watchedFiles(), (std::vector<std::string>{lib.string(), shape.string()}));
  rewrite(lib, "#define TURN 60\n");
  EXPECT_TRUE(model.refresh());
  model.regrow();
  EXPECT_EQ(model.modelVersion(), 4u) << model.state().dump(2);
  EXPECT_TRUE(model.state()["ok"].get<bool>());
}

// `--interpret music` on a program that declares no #interpret: the music set's notes,
// in seconds of the score's tempo (25 half beats at 160 a minute), and no 3-D model.
TEST_F(StudioFixture, TheSetsGivenAreTheOnesThatInterpret) {
  write("lsystem melody {\n  #music sequential\n  #tempo 160\n  #until 2\n  axiom Setup F\n"
        "  interpret music Setup { pitch(62) duration(0.5) }\n  F -> F + F - F - F + F\n}\n");
  StudioModelDef def = modelDef();
  StudioModel plain(def);
  plain.regrow();
  ASSERT_EQ(plain.modelVersion(), 1u) << plain.state().dump(2);
  EXPECT_TRUE(plain.notes().empty());
  EXPECT_FALSE(plain.glb().empty());
  def.sets = {"music"};
  StudioModel heard(def);
  heard.regrow();
  ASSERT_EQ(heard.modelVersion(), 1u) << heard.state().dump(2);
  const std::vector<StudioNote> notes = heard.notes();
  ASSERT_EQ(notes.size(), 25u);
  EXPECT_EQ(notes.back().start, 24 * 0.5 * 60 / 160);
  EXPECT_EQ(notes.back().duration, 0.5 * 60 / 160);
  EXPECT_TRUE(heard.glb().empty());
  EXPECT_FALSE(heard.state()["hasModel"].get<bool>());
}

// The frames the page steps through: --frames of them over [from, until], at the
// developmental time each was grown to.
TEST_F(StudioFixture, TheStateListsTheTimesOfTheFrames) {
  StudioModel model(modelDef());
  model.regrow();
  EXPECT_EQ(model.state()["frames"], nlohmann::json::array({0.0, 1.0, 2.0, 3.0}));
}

// An image-set model: a picture of each frame, served for the page to show at its time.
TEST_F(StudioFixture, AnImageModelsPicturesAreServedAFrameEach) {
  write("#until 3\n#interpret image\ncell C(v = 0) {\n  rules { v = v + 1; }\n"
        "  interpret image { range(0, 3) pixel(me.x, me.y, v) }\n}\n"
        "system glow {\n  pool grid(4, 4);\n  fill C(0);\n}\n");
  StudioModel model(modelDef());
  model.regrow();
  ASSERT_EQ(model.modelVersion(), 1u) << model.state().dump(2);
  EXPECT_EQ(model.state()["pictures"], 4);
  EXPECT_FALSE(model.state()["hasModel"].get<bool>());
  for (std::size_t frame = 0; frame < 4; ++frame)
    EXPECT_TRUE(model.picture(frame).starts_with("\x89PNG\r\n\x1a\n")) << frame;
  EXPECT_NE(model.picture(0), model.picture(3));  // every site a colour darker at the start
  EXPECT_TRUE(model.picture(4).empty());
  Gallery gallery(galleryDef());
  StudioServer server(model, gallery);
  auto get = [&](std::string path) {
    HttpRequest request;
    request.method = "GET";
    request.path = std::move(path);
    request.port = 8420;
    request.headers = {{"host", "127.0.0.1:8420"}};
    return server.handle(request);
  };
  const HttpResponse last = get("/model/picture/3.png");
  EXPECT_EQ(last.status, 200);
  EXPECT_EQ(last.contentType, "image/png");
  EXPECT_EQ(last.body, model.picture(3));
  EXPECT_EQ(get("/model/picture/4.png").status, 404);
  EXPECT_EQ(get("/model/picture/x.png").status, 404);
  EXPECT_EQ(get("/model/picture/.png").status, 404);
}

// Another tool's file, converted when read, is never written over with cell-language text:
// the slider's value can be dropped, not written.
TEST_F(StudioFixture, ASlidersValueIsNotWrittenIntoAConvertedFile) {
  StudioModelDef def = modelDef();
  def.program.read = [](const std::string& path, uint64_t, const WorldLimits&) {
    return StudioSource{std::string(kTree), path + " (converted)", "", nullptr, {}};
  };
  StudioModel model(def);
  model.regrow();
  ASSERT_EQ(model.modelVersion(), 1u) << model.state().dump(2);
  EXPECT_TRUE(model.state()["converted"].get<bool>());
  model.setDefine("LEN", 1.75);
  EXPECT_THROW(model.writeDefine("LEN"), std::invalid_argument);
  EXPECT_EQ(readText(file), kTree);
  model.dropDefine("LEN");
  EXPECT_EQ(model.defineValues().at("LEN"), 1.0);
}

// A save caught half-written (an editor truncates the file, then writes it): the errors of
// the half the studio read are not shown; it reads the file again once it changed, and
// shows the text the editor finished. A file that stays broken shows its errors.
TEST_F(StudioFixture, ASaveCaughtHalfWrittenFlashesNoErrors) {
  const std::string half = std::string(kTree).substr(0, std::string(kTree).size() / 2);
  write(half);
  StudioModelDef def = modelDef();
  int reads = 0;
  def.program.read = [&](const std::string& path, uint64_t, const WorldLimits&) {
    StudioSource read{readText(path), path, "", nullptr, {}};
    if (++reads == 1) write(kTree);  // the editor finishes just after the studio read
    return read;
  };
  StudioModel model(def);
  model.regrow();
  EXPECT_EQ(reads, 2);
  EXPECT_EQ(model.version(), 1u);  // the half's errors were never published
  EXPECT_EQ(model.modelVersion(), 1u) << model.state().dump(2);
  EXPECT_TRUE(model.state()["ok"].get<bool>()) << model.state()["diagnostics"].dump(2);

  write(half);
  EXPECT_TRUE(model.refresh());
  model.regrow();
  EXPECT_EQ(reads, 3);
  EXPECT_EQ(model.version(), 2u);
  EXPECT_EQ(model.modelVersion(), 1u);
  EXPECT_FALSE(model.state()["ok"].get<bool>());
}

// An L-Py file, converted as the command reads it: its diagnostics at the file's own
// lines, and the page shows the file as written (the converted text is one line longer
// at the top, so a line number of it would mark the wrong line).
TEST_F(StudioFixture, AConvertedFilesErrorsAreAtItsOwnLines) {
  const fs::path lpy = folder / "bad.lpy";
  const std::string original =
      "# a test\nAxiom: A(1)\nderivation length: 2\nproduction:\n\nA(x) --> F(x) A(y)\nendlsystem\n";
  std::ofstream(lpy, std::ios::binary) << original;
  StudioModelDef def = modelDef();
  def.program.file = lpy.string();
  def.program.read = [](const std::string& path, uint64_t maxBytes, const WorldLimits&) {
    auto source = std::make_shared<const SourceFile>(path, readText(path));
    DiagnosticSink sink;
    convert::ConvertResult converted = convert::convertFile(*source, convert::Dialect::LPy, "", sink, maxBytes);
    return StudioSource{std::move(converted.program), path + " (converted)", "", source,
                        std::move(converted.lineOrigins)};
  };
  StudioModel model(def);
  model.regrow();
  const nlohmann::json state = model.state();
  EXPECT_TRUE(state["converted"].get<bool>());
  EXPECT_EQ(state["source"], original);
  EXPECT_EQ(state["sourceName"], lpy.string());
  ASSERT_EQ(state["diagnostics"].size(), 1u) << state.dump(2);
  const nlohmann::json& error = state["diagnostics"][0];
  EXPECT_EQ(error["file"], lpy.string());
  EXPECT_EQ(error["line"], 6);
  EXPECT_EQ(error["column"], 1);
  EXPECT_TRUE(error["text"].get<std::string>().starts_with(lpy.string() + ":6:1: error: unknown name 'y'"))
      << error["text"];
  EXPECT_NE(error["text"].get<std::string>().find("\nA(x) --> F(x) A(y)\n"), std::string::npos) << error["text"];
  EXPECT_NE(model.text().find("A(x) -> F(x) A(y)"), std::string::npos);  // the converted text grows
}

// Growth without end for a page: 50 M steps of 1,000 cells (minutes; the step limit is
// 100 M). The growth is watched, answered about, stopped; the last model stays.
std::string endless() {
  std::string axiom;
  for (int i = 0; i < 1000; ++i) axiom += " A";
  return "lsystem endless {\n  #until 50000000\n  axiom" + axiom + "\n  A -> A\n}\n";
}

// Waits for a state in which `wanted` holds; the state then.
nlohmann::json waitForState(const StudioModel& model, const std::function<bool(const nlohmann::json&)>& wanted) {
  for (uint64_t seen = model.changes();; seen = model.waitForChange(seen, std::chrono::seconds(1))) {
    nlohmann::json state = model.state();
    if (wanted(state)) return state;
  }
}

TEST_F(StudioFixture, AStopCancelsTheGrowthAtHandAndTheLastModelStays) {
  StudioModel model(modelDef());
  model.regrow();
  ASSERT_EQ(model.modelVersion(), 1u);
  model.start();
  write(endless());
  ASSERT_TRUE(model.refresh());
  // The growth shows its progress frame by frame; the first at t = 0.
  const nlohmann::json growing = waitForState(model, [](const nlohmann::json& state) {
    return state["growth"]["running"].get<bool>() && state["growth"]["cells"].get<uint64_t>() > 0;
  });
  EXPECT_EQ(growing["growth"]["cells"], 1000);
  EXPECT_EQ(growing["growth"]["time"], 0.0);
  EXPECT_EQ(growing["version"], 1);  // the last growth's state, answered meanwhile
  model.stop();
  ASSERT_TRUE(model.waitIdle());
  const nlohmann::json stopped = model.state();
  EXPECT_TRUE(stopped["stopped"].get<bool>());
  EXPECT_FALSE(stopped["growth"]["running"].get<bool>());
  EXPECT_EQ(stopped["version"], 2);
  EXPECT_EQ(stopped["modelVersion"], 1);  // the tree that grew before
  ASSERT_EQ(stopped["diagnostics"].size(), 1u);
  EXPECT_EQ(stopped["diagnostics"][0]["severity"], "note");
  EXPECT_EQ(stopped["diagnostics"][0]["message"], "the growth was cancelled");

  // A newer request cancels the growth at hand and grows the newer text.
  model.requestGrowth();
  waitForState(model, [](const nlohmann::json& state) { return state["growth"]["cells"].get<uint64_t>() > 0; });
  write(kTree);
  ASSERT_TRUE(model.refresh());
  ASSERT_TRUE(model.waitIdle());
  EXPECT_EQ(model.modelVersion(), 2u);
  EXPECT_FALSE(model.state()["stopped"].get<bool>());
}

TEST_F(StudioFixture, InteractiveLimitsStopARunawayAndCanBeRaisedToTheCeiling) {
  StudioModelDef def = modelDef();
  def.program.limits.maxCells = 50'000;  // the ceiling, as --max-cells gives it
  StudioModel model(def);
  EXPECT_EQ(model.state()["limits"]["maxCells"], 50'000);  // the interactive default is above the ceiling
  EXPECT_EQ(model.state()["limits"]["maxMemoryBytes"], kStudioMaxMemoryBytes);
  EXPECT_THROW(model.setLimits(0, 64 << 20), std::invalid_argument);
  EXPECT_THROW(model.setLimits(50'001, 64 << 20), std::invalid_argument);
  EXPECT_THROW(model.setLimits(1000, 1000), std::invalid_argument);
  model.setLimits(1000, 64 << 20);
  write("lsystem runaway {\n  #until 40\n  axiom A\n  A -> F A A\n}\n");
  model.regrow();
  const nlohmann::json state = model.state();
  EXPECT_FALSE(state["ok"].get<bool>());
  ASSERT_FALSE(state["diagnostics"].empty());
  EXPECT_NE(state["diagnostics"][0]["message"].get<std::string>().find("past 1000 cells"), std::string::npos)
      << state.dump(2);
  EXPECT_EQ(state["limits"]["maxCells"], 1000);
}

// A growth in the studio passed the page's limit, not the command line's: its message
// names the page's control (or, at the ceiling, the flag that raises the ceiling), for the
// model and for the gallery's variants alike, which grow within the limits the page sets.
TEST_F(StudioFixture, ALimitsMessageNamesThePagesControlNotTheCommandLinesFlag) {
  StudioModelDef def = modelDef();
  def.program.limits.maxCells = 50'000;  // the ceiling, as the command line gives it
  def.program.limits.maxMemoryBytes = uint64_t{4} << 30;
  StudioModel model(def);
  model.setLimits(1000, 64 << 20);
  write("#define SPARE 1\nlsystem runaway {\n  #until 40\n  axiom A\n  A -> F A A\n}\n");
  auto firstDiagnostic = [&model] {
    const nlohmann::json state = model.state();
    return state["diagnostics"].empty() ? nlohmann::json::object() : state["diagnostics"][0];
  };
  model.regrow();
  EXPECT_EQ(firstDiagnostic()["message"],
            "the model grew past 1000 cells, the cell limit; raise it under Limits on the page (cells, up to 50000)");
  EXPECT_EQ(firstDiagnostic()["text"].get<std::string>().find("--max"), std::string::npos) << firstDiagnostic();
  model.setLimits(50'000, 64 << 20);
  model.regrow();
  EXPECT_EQ(firstDiagnostic()["message"],
            "the model grew past 50000 cells, the cell limit; the page's cell limit is at its ceiling: start the "
            "studio with a larger --max-cells N to raise it");
  model.setLimits(50'000, 1 << 20);
  model.regrow();
  // (Which part passes 1 MiB first is the writer's: the message ends the same.)
  const std::string memory = firstDiagnostic()["message"];
  EXPECT_TRUE(memory.ends_with("1 MiB; raise it under Limits on the page (memory, up to 4096 MiB)") ||
              memory.ends_with("1 MiB, the memory limit; raise it under Limits on the page (memory, up to 4096 MiB)"))
      << memory;

  GalleryDef gallerySettings = galleryDef();
  gallerySettings.program.limits = def.program.limits;
  Gallery gallery(gallerySettings);
  StudioServer server(model, gallery);
  ASSERT_EQ(askAsThePage(server, "POST", "/api/limits", R"({"maxCells": 2000, "maxMemoryMiB": 64})").status, 200);
  ASSERT_EQ(askAsThePage(server, "POST", "/api/gallery", "{}").status, 200);
  ASSERT_TRUE(server.waitForGallery(std::chrono::minutes(5)));
  const nlohmann::json variants = nlohmann::json::parse(askAsThePage(server, "GET", "/api/gallery", "").body)["variants"];
  ASSERT_EQ(variants.size(), 12u);
  EXPECT_EQ(variants[0]["error"],
            "the model grew past 2000 cells, the cell limit; raise it under Limits on the page (cells, up to 50000)");
}

// The interactive limits hold the reading of the program's file too, not only its growth:
// the reader (which refuses a file whose checking would pass the memory limit, and
// converts another tool's within it) is given the limits the page shows, and the ones
// it raises them to.
TEST_F(StudioFixture, TheInteractiveLimitsHoldTheReadingOfTheFile) {
  StudioModelDef def = modelDef();
  def.program.limits.maxCells = 50'000;
  def.program.limits.maxMemoryBytes = uint64_t{4} << 30;  // the ceiling, as the command line gives it
  def.maxMemoryBytes = 64 << 20;
  std::vector<WorldLimits> given;
  def.program.read = [&given](const std::string& path, uint64_t, const WorldLimits& limits) {
    given.push_back(limits);
    if (limits.maxMemoryBytes < (96 << 20))  // as a reader refuses a file past the limit
      return StudioSource{std::nullopt, path, "checking it needs about 80 MiB, past the memory limit", nullptr, {}};
    return StudioSource{readText(path), path, "", nullptr, {}};
  };
  StudioModel model(def);
  model.regrow();
  ASSERT_EQ(given.size(), 1u);
  EXPECT_EQ(given[0].maxMemoryBytes, uint64_t{64} << 20);
  EXPECT_EQ(given[0].maxCells, 50'000u);
  EXPECT_EQ(model.modelVersion(), 0u);
  const nlohmann::json refused = model.state();
  ASSERT_EQ(refused["diagnostics"].size(), 1u) << refused.dump(2);
  EXPECT_EQ(refused["diagnostics"][0]["message"],
            "cannot read or convert " + file.string() + ": checking it needs about 80 MiB, past the memory limit");
  model.setLimits(40'000, 128 << 20);
  model.regrow();
  ASSERT_EQ(given.size(), 2u);
  EXPECT_EQ(given[1].maxMemoryBytes, uint64_t{128} << 20);
  EXPECT_EQ(given[1].maxCells, 40'000u);
  EXPECT_EQ(model.modelVersion(), 1u) << model.state().dump(2);
}

// A define's #range bounds what the page may give it: a value outside is refused (one
// such request grew a model until memory ran out) and nothing grows; the range's ends
// are taken.
TEST_F(StudioFixture, ADefineOutsideItsDeclaredRangeIsRefusedAndGrowsNothing) {
  write("#define DEPTH 4\n#range DEPTH 2 6\nlsystem s {\n  #until 3\n  axiom A(DEPTH)\n"
        "  A(n) : n > 0 -> F [ + A(n - 1) ] A(n - 1)\n}\n");
  StudioModel model(modelDef());
  model.regrow();
  model.start();
  Gallery gallery(galleryDef());
  StudioServer server(model, gallery);
  for (const char* value : {"1", "7", "1e308", "-6"}) {
    const HttpResponse refused =
        askAsThePage(server, "POST", "/api/define", std::string(R"({"name": "DEPTH", "value": )") + value + "}");
    EXPECT_EQ(refused.status, 422) << value;
    EXPECT_NE(refused.body.find("is outside its range [2, 6]"), std::string::npos) << refused.body;
  }
  EXPECT_EQ(model.version(), 1u);
  EXPECT_EQ(model.defines().at(0).value, 4);
  EXPECT_EQ(askAsThePage(server, "POST", "/api/define", R"({"name": "DEPTH", "value": 6})").status, 200);
  ASSERT_TRUE(model.waitIdle());
  EXPECT_EQ(model.modelVersion(), 2u);
  EXPECT_EQ(model.defines().at(0).value, 6);
}

TEST_F(StudioFixture, RoutesAnswerThePage) {
  StudioModel model(modelDef());
  model.regrow();
  model.start();
  Gallery gallery(galleryDef());
  StudioServer server(model, gallery);
  auto ask = [&](std::string method, std::string path, std::string body = "") {
    return askAsThePage(server, std::move(method), std::move(path), std::move(body));
  };
  const HttpResponse state = ask("GET", "/api/state");
  EXPECT_EQ(state.status, 200);
  EXPECT_EQ(nlohmann::json::parse(state.body)["modelVersion"], 1);
  const HttpResponse glb = ask("GET", "/model.glb");
  EXPECT_EQ(glb.contentType, "model/gltf-binary");
  EXPECT_EQ(glb.body, model.glb());
  EXPECT_EQ(ask("GET", "/nowhere").status, 404);
  EXPECT_EQ(ask("DELETE", "/api/state").status, 405);
  EXPECT_EQ(ask("POST", "/api/define", "not json").status, 400);
  EXPECT_EQ(ask("POST", "/api/define", R"({"name": "LEN"})").status, 400);
  EXPECT_EQ(ask("POST", "/api/define", R"({"name": "NOPE", "value": 1})").status, 422);
  EXPECT_EQ(ask("POST", "/api/define", R"({"name": "ANGLE", "value": 61})").status, 422);  // past its range
  EXPECT_EQ(ask("POST", "/api/define", R"({"name": "ANGLE", "value": 1e308})").status, 422);
  EXPECT_EQ(model.version(), 1u);
  const HttpResponse moved = ask("POST", "/api/define", R"({"name": "ANGLE", "value": 45})");
  EXPECT_EQ(moved.status, 200);
  ASSERT_TRUE(model.waitIdle());
  EXPECT_EQ(model.modelVersion(), 2u);
  EXPECT_EQ(ask("POST", "/api/limits", R"({"maxCells": -1, "maxMemoryMiB": 64})").status, 400);
  EXPECT_EQ(ask("POST", "/api/limits", R"({"maxCells": 0, "maxMemoryMiB": 64})").status, 422);
  const HttpResponse limited = ask("POST", "/api/limits", R"({"maxCells": 5000, "maxMemoryMiB": 64})");
  EXPECT_EQ(limited.status, 200);
  EXPECT_EQ(nlohmann::json::parse(limited.body)["limits"]["maxMemoryBytes"], 64 << 20);
  ASSERT_TRUE(model.waitIdle());
  EXPECT_EQ(model.modelVersion(), 3u);
  // A slider's value written into the file or dropped (as the page's two buttons do).
  EXPECT_EQ(ask("POST", "/api/define/write", R"({"name": "ANGLE", "path": "/tmp/x"})").status, 400);
  EXPECT_EQ(ask("POST", "/api/define/drop", R"({"name": "LEN"})").status, 422);  // no slider value
  const HttpResponse dropped = ask("POST", "/api/define/drop", R"({"name": "ANGLE"})");
  EXPECT_EQ(dropped.status, 200);
  EXPECT_EQ(nlohmann::json::parse(dropped.body)["state"]["defines"][0]["value"], 30.0);
  ASSERT_TRUE(model.waitIdle());
  ASSERT_EQ(ask("POST", "/api/define", R"({"name": "ANGLE", "value": 45})").status, 200);
  ASSERT_TRUE(model.waitIdle());
  const HttpResponse written = ask("POST", "/api/define/write", R"({"name": "ANGLE"})");
  EXPECT_EQ(written.status, 200);
  EXPECT_EQ(nlohmann::json::parse(written.body)["path"], file.string());
  EXPECT_EQ(readText(file).substr(0, 16), "#define ANGLE 45");
  ASSERT_TRUE(model.waitIdle());
  EXPECT_EQ(model.modelVersion(), 6u);  // dropped, moved, written: three growths
  EXPECT_EQ(ask("POST", "/api/stop", "{}").status, 200);
  EXPECT_EQ(nlohmann::json::parse(ask("GET", "/api/notes").body)["notes"].size(), 0u);  // no music set

  // Only a POST makes the gallery; a GET answers it as it stands.
  EXPECT_EQ(nlohmann::json::parse(ask("GET", "/api/gallery").body)["generation"], 0);
  EXPECT_FALSE(gallery.ready());
  EXPECT_EQ(nlohmann::json::parse(ask("POST", "/api/gallery", "{}").body)["generation"], 1);
  ASSERT_TRUE(server.waitForGallery(std::chrono::minutes(5)));
  const nlohmann::json first = nlohmann::json::parse(ask("GET", "/api/gallery").body);
  ASSERT_EQ(first["variants"].size(), 12u);
  // The gallery starts from the sliders: variant 0 is the program as the page shows it.
  EXPECT_EQ(first["variants"][0]["values"], nlohmann::json::array({45.0, 1.0}));
  EXPECT_EQ(ask("GET", "/gallery/0.png").contentType, "image/png");
  EXPECT_TRUE(ask("GET", "/gallery/0.png").body.starts_with("\x89PNG"));
  EXPECT_EQ(ask("GET", "/gallery/12.png").status, 404);
  EXPECT_EQ(ask("GET", "/gallery/x.png").status, 404);
  EXPECT_EQ(ask("POST", "/api/breed", R"({"picked": []})").status, 422);
  EXPECT_EQ(ask("POST", "/api/breed", R"({"picked": [40]})").status, 422);
  const nlohmann::json second = nlohmann::json::parse(ask("POST", "/api/breed", R"({"picked": [2, 5]})").body);
  EXPECT_EQ(second["generation"], 2);
  EXPECT_EQ(second["variants"][0]["values"], first["variants"][2]["values"]);
  EXPECT_EQ(second["variants"][1]["values"], first["variants"][5]["values"]);
  const nlohmann::json saved = nlohmann::json::parse(ask("POST", "/api/save", R"({"index": 4})").body);
  const fs::path path = saved["path"].get<std::string>();
  EXPECT_EQ(path, folder / "tree_g2_v4.cell");
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  DiagnosticSink sink;
  const auto program = compileSource(path.string(), text, sink);
  ASSERT_TRUE(program) << text;
  EXPECT_EQ(program->defines[0].value, second["variants"][4]["values"][0].get<double>());
  EXPECT_EQ(program->defines[1].value, second["variants"][4]["values"][1].get<double>());
}

// The studio's own address and page over a real socket: what a browser sends for the
// studio's page, for another site's page (a "simple" cross-site POST, no preflight) and
// for a page of a site whose name was made to point at 127.0.0.1 (DNS rebinding).
struct StudioOverHttp : StudioFixture {
  std::unique_ptr<StudioModel> model;
  std::unique_ptr<Gallery> gallery;
  std::unique_ptr<StudioServer> studio;
  std::unique_ptr<HttpServer> http;
  std::string self;  // 127.0.0.1:PORT

  void SetUp() override {
    StudioFixture::SetUp();
    model = std::make_unique<StudioModel>(modelDef());
    model->regrow();
    model->start();
    GalleryDef def = galleryDef();
    def.saveTo = folder / "saved";
    fs::create_directories(def.saveTo);
    gallery = std::make_unique<Gallery>(def);
    gallery->reset(kTree, "tree");  // a gallery to save from
    gallery->growAll();
    studio = std::make_unique<StudioServer>(*model, *gallery);
    http = std::make_unique<HttpServer>(HttpServerDef{}, [this](const HttpRequest& r) { return studio->handle(r); });
    http->start();
    self = "127.0.0.1:" + std::to_string(http->port());
  }
  void TearDown() override {
    http->stop();
    studio.reset();  // and with it the gallery's thread, which grows variants into the folder
    StudioFixture::TearDown();
  }
  // The answer to a request with these header lines (each "Name: value"), whole.
  std::string send(const std::string& method, const std::string& path, const std::vector<std::string>& headers,
                   const std::string& body = "") {
    std::string request = method + " " + path + " HTTP/1.1\r\n";
    for (const std::string& header : headers) request += header + "\r\n";
    if (method == "POST") request += "Content-Length: " + std::to_string(body.size()) + "\r\n";
    return exchange(http->port(), request + "Connection: close\r\n\r\n" + body);
  }
  // What the studio's page sends for a change.
  std::vector<std::string> page() const {
    return {"Host: " + self, "Origin: http://" + self, "Content-Type: application/json", "X-Ontogen-Token: " + studio->token()};
  }
  // The programs in the test's folder, the save folder (saved/) among them.
  std::set<fs::path> cellFiles() const {
    std::set<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.path().extension() == ".cell") files.insert(entry.path());
    return files;
  }
};

int statusOf(const std::string& answer) { return answer.size() > 12 ? std::atoi(answer.c_str() + 9) : 0; }

TEST_F(StudioOverHttp, AForeignHostIsRefusedEvenToRead) {
  const std::string own = send("GET", "/api/state", {"Host: " + self});
  EXPECT_EQ(statusOf(own), 200) << own;
  EXPECT_NE(own.find("lsystem tree"), std::string::npos);  // the program's source
  EXPECT_EQ(statusOf(send("GET", "/api/state", {"Host: localhost:" + std::to_string(http->port())})), 200);
  const std::string port = std::to_string(http->port());
  for (const std::string& host : std::vector<std::string>{"Host: evil.example:" + port, "Host: attacker.com",
                                  "Host: 127.0.0.1:" + std::to_string(http->port() + 1), "Host: 127.0.0.1",
                                  "Host: 127.0.0.1:" + port + ".attacker.com", "X-No-Host: 1"}) {
    for (const char* path : {"/api/state", "/", "/model.glb", "/api/events"}) {
      const std::string answer = send("GET", path, {host});
      EXPECT_EQ(statusOf(answer), 403) << host << " " << path << "\n" << answer;
      EXPECT_EQ(answer.find("lsystem tree"), std::string::npos) << host;
      EXPECT_NE(answer.find("the studio answers only requests to 127.0.0.1:" + port), std::string::npos) << answer;
    }
    std::vector<std::string> headers = page();
    headers[0] = host;
    EXPECT_EQ(statusOf(send("POST", "/api/stop", headers, "{}")), 403) << host;
  }
}

TEST_F(StudioOverHttp, ACrossSiteSimplePostIsRefusedAndChangesNothing) {
  const std::set<fs::path> before = cellFiles();
  const uint64_t version = model->version();
  for (const std::string& origin : {std::string("Origin: http://evil.example"), std::string("Origin: null"),
                                    "Origin: https://" + self, "Origin: http://" + self + ".evil.example",
                                    std::string("X-No-Origin: 1")}) {
    for (const auto& [path, body] : std::vector<std::pair<std::string, std::string>>{
             {"/api/save", R"({"index": 0})"},
             {"/api/define", R"({"name": "ANGLE", "value": 45})"},
             {"/api/breed", R"({"picked": [1]})"},
             {"/api/limits", R"({"maxCells": 10, "maxMemoryMiB": 64})"},
             {"/api/stop", "{}"}}) {
      // As a form or fetch(..., {mode: "no-cors"}) of another site sends it: no preflight.
      const std::string simple = send("POST", path, {"Host: " + self, origin, "Content-Type: text/plain"}, body);
      EXPECT_EQ(statusOf(simple), 403) << origin << " " << path << "\n" << simple;
      EXPECT_NE(simple.find("own page"), std::string::npos) << simple;
      // Even with the token (were it ever to leak), another origin is refused.
      std::vector<std::string> headers = page();
      headers[1] = origin;
      EXPECT_EQ(statusOf(send("POST", path, headers, body)), 403) << origin << " " << path;
    }
  }
  EXPECT_EQ(cellFiles(), before);
  EXPECT_EQ(gallery->generation(), 1);
  EXPECT_EQ(model->version(), version);
  EXPECT_EQ(model->defineValues().at("ANGLE"), 30.0);  // as written
}

TEST_F(StudioOverHttp, AChangeNeedsThePagesTokenAndIsAnsweredWithIt) {
  const std::string token = studio->token();
  ASSERT_EQ(token.size(), 64u);
  std::string wrong = token;
  wrong[17] = wrong[17] == '0' ? '1' : '0';
  const std::string body = R"({"name": "ANGLE", "value": 45})";
  const uint64_t version = model->version();
  for (const std::string& given : {std::string(), "X-Ontogen-Token: " + wrong, "X-Ontogen-Token: " + token.substr(0, 63),
                                   "X-Ontogen-Token: " + token + "0", std::string("X-Ontogen-Token: "),
                                   "X-Ontogen-Token: " + studio->token().substr(0, 32)}) {
    std::vector<std::string> headers = page();
    headers[3] = given.empty() ? "X-Other: 1" : given;
    const std::string refused = send("POST", "/api/define", headers, body);
    EXPECT_EQ(statusOf(refused), 403) << given << "\n" << refused;
    EXPECT_NE(refused.find("the page's token (X-Ontogen-Token)"), std::string::npos) << refused;
  }
  EXPECT_EQ(model->version(), version);
  // The page's own request, from either of the studio's names.
  const std::string accepted = send("POST", "/api/define", page(), body);
  EXPECT_EQ(statusOf(accepted), 200) << accepted;
  ASSERT_TRUE(model->waitIdle());
  EXPECT_EQ(model->defineValues().at("ANGLE"), 45.0);
  EXPECT_GT(model->version(), version);
  const std::string local = "localhost:" + std::to_string(http->port());
  const std::string other = send("POST", "/api/stop", {"Host: " + local, "Origin: http://" + local, "X-Ontogen-Token: " + token}, "{}");
  EXPECT_EQ(statusOf(other), 200) << other;
  // A different run has a different token; the page it serves holds its own.
  EXPECT_NE(StudioServer(*model, *gallery).token(), token);
  const std::string served = send("GET", "/", {"Host: " + self});
  EXPECT_EQ(statusOf(served), 200);
  if (!studioAssets().empty()) {
    EXPECT_NE(served.find("<meta name=\"ontogen-token\" content=\"" + token + "\">"), std::string::npos) << served;
    EXPECT_EQ(served.find("ONTOGEN-PAGE-TOKEN"), std::string::npos);
  }
}

TEST_F(StudioOverHttp, TheStudioNamesWhatItSavesAndWritesNothingOutsideItsFolder) {
  const std::set<fs::path> before = cellFiles();
  for (const std::string& body :
       {std::string(R"({"index": 0, "name": "../escaped.cell"})"), std::string(R"({"index": "../escaped.cell"})"),
        std::string(R"({"index": 0, "path": "/tmp/escaped.cell"})"), std::string(R"({"name": "../../escaped.cell"})"),
        std::string(R"({"index": 0, "file": "sub/escaped.cell"})"), std::string(R"({"index": 0.5})")}) {
    const std::string answer = send("POST", "/api/save", page(), body);
    EXPECT_EQ(statusOf(answer), 400) << body << "\n" << answer;
  }
  EXPECT_EQ(cellFiles(), before);
  EXPECT_FALSE(fs::exists(folder / "escaped.cell"));
  EXPECT_FALSE(fs::exists("/tmp/escaped.cell"));
  const std::string saved = send("POST", "/api/save", page(), R"({"index": 3})");
  ASSERT_EQ(statusOf(saved), 200) << saved;
  EXPECT_NE(saved.find(nlohmann::json((folder / "saved" / "tree_g1_v3.cell").string()).dump()), std::string::npos)
      << saved;
  EXPECT_TRUE(fs::exists(folder / "saved" / "tree_g1_v3.cell"));
}

}  // namespace
}  // namespace ontogen::studio
