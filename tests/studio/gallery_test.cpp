// The studio's gallery (studio/gallery.h): what it varies, how it grows off the request's
// thread, what it saves, and that it is the same for the same seed and picks.

#include <chrono>
#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "studio/gallery.h"
#include "studio/gallery_grower.h"
#include "studio/studio_model.h"
#include "studio/studio_server.h"
#include "tests/studio/studio_fixture.h"

namespace ontogen::studio {
namespace {

namespace fs = std::filesystem;

using test::kTree;
using test::StudioFixture;

// A request that makes a generation is answered before its variants grow: they grow one
// after the other on the gallery's own thread, and a generation made meanwhile replaces
// the one growing, whose pictures are never shown as the new one's.
TEST_F(StudioFixture, AGalleryGrowsOffTheRequestsThreadAndANewGenerationReplacesTheOneGrowing) {
  StudioModel model(modelDef());
  model.regrow();
  Gallery gallery(galleryDef());
  auto server = std::make_unique<StudioServer>(model, gallery);
  auto ask = [&](std::string method, std::string path, std::string body = "") {
    return askAsThePage(*server, std::move(method), std::move(path), std::move(body));
  };
  // Answered before any probe of what changes the picture grew: the variants come after.
  const nlohmann::json asked = nlohmann::json::parse(ask("POST", "/api/gallery", "{}").body);
  EXPECT_EQ(asked["probing"], true);
  EXPECT_EQ(asked["probed"], 0);
  EXPECT_EQ(asked["variants"].size(), 0u);
  EXPECT_EQ(asked["growing"], true);
  EXPECT_EQ(ask("POST", "/api/breed", R"({"picked": [0]})").status, 422);  // nothing to pick yet
  nlohmann::json first = asked;
  for (const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(5);
       first["probing"] == true && std::chrono::steady_clock::now() < until;)
    first = nlohmann::json::parse(ask("GET", "/api/gallery").body);
  ASSERT_EQ(first["variants"].size(), 12u);
  EXPECT_EQ(first["epoch"], asked["epoch"]);
  // The program as written grew as the first probe: variant 0 has its picture at once.
  EXPECT_EQ(first["variants"][0]["grown"], true);
  EXPECT_EQ(first["variants"][0]["picture"], true);
  // Picked before it has grown: a variant's values are known at once.
  const nlohmann::json second = nlohmann::json::parse(ask("POST", "/api/breed", R"({"picked": [3]})").body);
  EXPECT_EQ(second["generation"], 2);
  EXPECT_EQ(second["grown"], 0);
  EXPECT_EQ(second["variants"][0]["values"], first["variants"][3]["values"]);
  ASSERT_TRUE(server->waitForGallery(std::chrono::minutes(5)));
  const nlohmann::json grown = nlohmann::json::parse(ask("GET", "/api/gallery").body);
  EXPECT_EQ(grown["generation"], 2);
  EXPECT_EQ(grown["epoch"], second["epoch"]);
  EXPECT_EQ(grown["grown"], 12);
  EXPECT_EQ(grown["growing"], false);
  // Each picture is its own variant's, grown again here on this thread.
  Gallery again(galleryDef());
  for (int i = 0; i < 12; ++i) {
    const GalleryVariant& variant = gallery.variants()[static_cast<std::size_t>(i)];
    ASSERT_TRUE(variant.grown);
    ASSERT_FALSE(variant.png.empty()) << variant.error;
    EXPECT_EQ(ask("GET", "/gallery/" + std::to_string(i) + ".png").body, variant.png);
    EXPECT_EQ(again.grow(GalleryTask{0, i, false, variant.text, "tree"}).png, variant.png) << "variant " << i;
  }
  // A studio closed while its gallery grows cancels the variant growing and ends.
  EXPECT_EQ(nlohmann::json::parse(ask("POST", "/api/gallery/restart", "{}").body)["grown"], 0);
  server.reset();
}

// The name a variant is saved under is the gallery's: a stem with separators or ".."
// (from a file named so) still lands in the save folder.
TEST_F(StudioFixture, ASavedVariantStaysInTheSaveFolderWhateverItsStem) {
  GalleryDef def = galleryDef();
  def.saveTo = folder / "saved" / "here";
  fs::create_directories(def.saveTo);
  Gallery gallery(def);
  for (const std::string& stem : {std::string("../../escaped"), std::string("/etc/escaped"), std::string(".."),
                                  std::string("a/../b"), std::string("..\\x")}) {
    gallery.reset("#define A 1\nlsystem s {\n  #until 1\n  axiom F(A)\n}\n", stem);
    gallery.growAll();
    const fs::path path = gallery.save(0);
    EXPECT_EQ(path.parent_path(), folder / "saved" / "here") << stem << " -> " << path;
    EXPECT_EQ(path.filename().string().find(".."), std::string::npos) << path;
    EXPECT_NE(path.filename().string()[0], '.') << path;
    EXPECT_TRUE(fs::exists(path)) << path;
  }
  EXPECT_FALSE(fs::exists(folder / "escaped_g1_v0.cell"));
}

// A program with nothing to vary makes a gallery of twelve of the same: the gallery says
// so, and what would vary it.
TEST_F(StudioFixture, AGalleryWarnsWhenNothingWouldVary) {
  Gallery varied(galleryDef());
  varied.reset(kTree, "tree");
  EXPECT_EQ(varied.state()["warning"], "");
  const std::string fixed = "lsystem fixed {\n  #until 2\n  axiom A\n  A -> F [ + A ] A\n}\n";
  Gallery same(galleryDef());
  same.reset(fixed, "fixed");
  EXPECT_EQ(same.state()["warning"],
            "the program has no #define NAME NUMBER to vary: every variant is the same (vary its rules' numbers "
            "with --vary-constants)");
  GalleryDef constants = galleryDef();
  constants.constants = true;
  Gallery none(constants);
  none.reset("lsystem fixed {\n  #until 2\n  axiom A\n  A -> F [ + A ] A\n}\n", "fixed");
  EXPECT_EQ(none.state()["warning"], "the program has no #define NAME NUMBER and no number in its rules to vary: "
                                     "every variant is the same");
}

// Variants must differ visibly: a define that does not change the picture (here one of
// the music alone) is held at its value, and the gallery varies the one that does.
TEST_F(StudioFixture, AGalleryVariesTheDefinesThatChangeThePictureAndHoldsTheOthers) {
  const std::string music = R"(#define VOLUME 80
#range VOLUME 1 127
lsystem tree {
  #until 3
  axiom !(0.1) (A, 0)
  (A, 1) -> F [ +(ANGLE) (A, 0) ] [ -(ANGLE) (A, 0) ]
  interpret music A { pitch(60) note(0.25, VOLUME) }
}
)";
  Gallery gallery(galleryDef());
  gallery.reset("#define ANGLE 30\n" + music, "tree");
  EXPECT_TRUE(gallery.probing());
  EXPECT_TRUE(gallery.variants().empty());
  // The program as written, then ANGLE at 0 and 60, VOLUME at 1 and 127.
  EXPECT_EQ(gallery.state()["probes"], 5);
  gallery.growAll();
  const nlohmann::json state = gallery.state();
  EXPECT_FALSE(gallery.probing());
  // ANGLE at 0 pictured a straight stem: its high end was not needed.
  EXPECT_EQ(state["probes"], 4);
  EXPECT_EQ(state["probed"], 4);
  EXPECT_EQ(state["held"], nlohmann::json::array({"VOLUME"}));
  EXPECT_EQ(state["warning"], "");
  ASSERT_EQ(state["genes"].size(), 1u);
  EXPECT_EQ(state["genes"][0]["name"], "ANGLE");
  std::set<double> angles;
  std::set<std::string> pictures;
  for (const GalleryVariant& variant : gallery.variants()) {
    ASSERT_EQ(variant.genome.values.size(), 1u);
    angles.insert(variant.genome.values[0]);
    EXPECT_NE(variant.text.find("#define VOLUME 80\n"), std::string::npos) << variant.text;
    EXPECT_TRUE(variant.error.empty()) << variant.error;
    pictures.insert(variant.png);
  }
  // ANGLE is written as a whole number, so two variants may share one: each other one
  // looks different.
  EXPECT_GE(angles.size(), 10u);
  EXPECT_EQ(pictures.size(), angles.size());

  // A program whose only define changes nothing it pictures says so, and grows once.
  Gallery quiet(galleryDef());
  const std::string unseen = music.substr(0, music.find("lsystem")) +
                             "lsystem tree {\n  #until 3\n  axiom F(1) A\n"
                             "  interpret music A { pitch(60) note(0.25, VOLUME) }\n}\n";
  quiet.reset("#define ANGLE 30\n" + unseen, "tree");
  quiet.growAll();
  EXPECT_EQ(quiet.state()["held"], nlohmann::json::array({"ANGLE", "VOLUME"}));
  EXPECT_EQ(quiet.state()["warning"],
            "no #define changes the picture between the ends of its range (ANGLE, VOLUME): every variant is the same "
            "(vary its rules' numbers with --vary-constants)");
  for (const GalleryVariant& variant : quiet.variants()) {
    EXPECT_TRUE(variant.grown);
    EXPECT_FALSE(variant.png.empty());
    EXPECT_EQ(variant.png, quiet.variants()[0].png);
  }
}

// A grower that ends (the studio closing) cancels the probe or variant growing: what the
// cancelled growth gave is no outcome of it, and is not kept as its picture (a probe kept
// so would count as changing the picture). The gallery grows it again under another.
TEST_F(StudioFixture, AGrowerThatEndsKeepsNothingOfTheGrowthItCancelled) {
  Gallery gallery(galleryDef());
  // 50 M steps of 1,000 cells: minutes, far longer than the wait below.
  std::string cells;
  for (int i = 0; i < 1000; ++i) cells += " A";
  gallery.reset("#define SPARE 1\nlsystem endless {\n  #until 50000000\n  axiom" + cells + "\n  A -> A\n}\n",
                "endless");
  ASSERT_TRUE(gallery.probing());
  {
    GalleryGrower grower(gallery);
    // Whether or not the probe has started growing when the grower ends, none is kept.
    EXPECT_FALSE(grower.waitGrown(std::chrono::milliseconds(500)));
  }
  const nlohmann::json state = gallery.state();
  EXPECT_EQ(state["probed"], 0) << state.dump();
  EXPECT_TRUE(gallery.probing());
  ASSERT_TRUE(gallery.nextTask().has_value());
  EXPECT_TRUE(gallery.nextTask()->probe);
  EXPECT_EQ(gallery.nextTask()->index, 0);
}

TEST_F(StudioFixture, GalleryIsTheSameForTheSameSeedAndPicks) {
  Gallery a(galleryDef(7)), b(galleryDef(7)), c(galleryDef(8));
  a.reset(kTree, "tree");
  b.reset(kTree, "tree");
  c.reset(kTree, "tree");
  a.growAll();
  b.growAll();
  c.growAll();
  std::vector<Genome> genomesA, genomesC;
  for (std::size_t i = 0; i < a.variants().size(); ++i) {
    EXPECT_EQ(a.variants()[i].genome, b.variants()[i].genome);
    EXPECT_EQ(a.variants()[i].png, b.variants()[i].png);
    EXPECT_TRUE(a.variants()[i].error.empty()) << a.variants()[i].error;
  }
  EXPECT_EQ(a.variants()[0].genome, a.space().original());
  bool differs = false;
  for (std::size_t i = 1; i < a.variants().size(); ++i) differs = differs || a.variants()[i].genome != c.variants()[i].genome;
  EXPECT_TRUE(differs);
  a.breed({1, 4, 9});
  b.breed({1, 4, 9});
  for (std::size_t i = 0; i < a.variants().size(); ++i) EXPECT_EQ(a.variants()[i].genome, b.variants()[i].genome);
  EXPECT_THROW(a.breed({}), std::invalid_argument);
  EXPECT_THROW(a.save(12), std::invalid_argument);
}

}  // namespace
}  // namespace ontogen::studio
