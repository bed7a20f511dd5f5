#pragma once
// What the studio's tests share: a tree program written into a folder of the test's own,
// the settings of a model and a gallery of it, and a way to ask the studio as its page does.

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "studio/gallery.h"
#include "studio/http_server.h"
#include "studio/studio_model.h"
#include "studio/studio_server.h"

namespace ontogen::studio::test {

namespace fs = std::filesystem;

inline constexpr const char* kTree = R"(#define ANGLE 30
#define LEN 1
lsystem tree {
  #until 3
  axiom !(0.1) (A, 0)
  (A, 1) -> F(LEN) [ +(ANGLE) (A, 0) ] [ -(ANGLE) (A, 0) ]
}
)";

struct StudioFixture : ::testing::Test {
  fs::path folder;
  fs::path file;
  void SetUp() override {
    folder = fs::temp_directory_path() / ("ontogen_studio_test_" + std::to_string(::getpid()) + "_" +
                                          ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder);
    fs::create_directories(folder);
    file = folder / "tree.cell";
    write(kTree);
  }
  void TearDown() override { fs::remove_all(folder); }
  void write(const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
    // File times may be coarse: a rewrite must look different to refresh().
    fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(++rewrites));
  }
  StudioModelDef modelDef() {
    StudioModelDef def;
    def.program.file = file.string();
    def.frames = 4;
    def.work = folder / "work";
    return def;
  }
  // As the page asks: to the studio's address, its changes from its origin with the token.
  static HttpResponse askAsThePage(StudioServer& server, std::string method, std::string path, std::string body) {
    HttpRequest request;
    request.method = std::move(method);
    request.path = std::move(path);
    request.body = std::move(body);
    request.port = 8420;
    request.headers = {{"host", "127.0.0.1:8420"}, {"origin", "http://127.0.0.1:8420"}, {"x-ontogen-token", server.token()}};
    return server.handle(request);
  }
  GalleryDef galleryDef(uint64_t seed = 7) {
    GalleryDef def;
    def.program.file = file.string();
    def.seed = seed;
    def.thumbnailSide = 64;
    def.work = folder / "gallery";
    def.saveTo = folder;
    return def;
  }
  int rewrites = 0;
};

}  // namespace ontogen::studio::test
