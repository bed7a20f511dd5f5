// Fuzz target: one connection's bytes to the studio, parsed by its HTTP library and
// answered by its routes (HttpServer::answerBytes over StudioServer::handle), against a
// small model and gallery made afresh for each input, so that inputs do not depend on one
// another. A define or limit a request sets is then grown with. Besides the sanitizers it
// checks what the studio promises whatever the bytes:
//   - a request to another Host is refused (403), and so is a change without the page's
//     Origin and token (studio/request_guard.h);
//   - every JSON answer is valid JSON;
//   - a saved variant lands in the save folder.
// The seeds (seeds/request/) are raw requests to 127.0.0.1:8420 with kToken.

#include <unistd.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "studio/gallery.h"
#include "studio/http_server.h"
#include "studio/studio_model.h"
#include "studio/studio_server.h"
#include "tests/fuzz/fuzz_limits.h"

namespace {

using namespace ontogen;
using namespace ontogen::studio;
namespace fs = std::filesystem;

constexpr uint16_t kPort = 8420;
// The page's token the seeds carry.
constexpr const char* kToken = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";

// Two defines with their sliders, a music set and geometry: every route has something to say.
constexpr const char* kProgram = R"(#define ANGLE 30
#define LEN 1
#range LEN 0.5 2
#interpret geometry
#interpret music
lsystem tree {
  #until 3
  axiom !(0.1) (A, 0)
  (A, 1) -> F(LEN) [ +(ANGLE) (A, 0) ] [ -(ANGLE) (A, 0) ]
  interpret music A { pitch(60) note(0.25, 90) }
}
)";

struct Place {
  fs::path folder, file, saved;
  Place() {
    folder = fs::temp_directory_path() / ("ontogen-fuzz-request-" + std::to_string(::getpid()));
    fs::create_directories(folder / "saved");
    file = folder / "tree.cell";
    saved = folder / "saved";
    std::ofstream(file, std::ios::binary) << kProgram;
  }
};

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// What the studio promises of its answer to a request, checked apart from how it keeps it.
void check(const HttpRequest& request, const HttpResponse& response, const fs::path& saved) {
  const std::string port = ":" + std::to_string(kPort);
  const std::string host = lower(request.header("host"));
  if (host != "127.0.0.1" + port && host != "localhost" + port && response.status != 403) std::abort();
  if (request.method != "GET" && request.method != "HEAD") {
    const std::string origin = request.header("origin");
    const bool page = (origin == "http://127.0.0.1" + port || origin == "http://localhost" + port) &&
                      request.headers.count("x-ontogen-token") && request.headers.at("x-ontogen-token") == kToken;
    if (!page && response.status != 403) std::abort();
  }
  if (response.contentType != "application/json") return;
  const nlohmann::json answer = nlohmann::json::parse(response.body, nullptr, false);
  if (answer.is_discarded()) std::abort();
  if (request.path == "/api/save" && response.status == 200 &&
      fs::path(answer.at("path").get<std::string>()).parent_path() != saved)
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Place place;
  StudioModelDef modelDef;
  modelDef.program.file = place.file.string();
  modelDef.program.limits = fuzz::growLimits();  // the ceiling a request may raise the limits to
  modelDef.program.maxSourceBytes = fuzz::kMaxSourceBytes;
  modelDef.maxCells = 1000;
  modelDef.maxMemoryBytes = uint64_t{32} << 20;
  modelDef.frames = 4;
  modelDef.work = place.folder / "work";
  StudioModel model(modelDef);
  model.regrow();
  GalleryDef galleryDef;
  galleryDef.program = modelDef.program;
  galleryDef.size = 3;
  galleryDef.thumbnailSide = 16;
  galleryDef.work = place.folder / "gallery";
  galleryDef.saveTo = place.saved;
  Gallery gallery(galleryDef);
  StudioServer studio(model, gallery, StudioServerDef{.token = kToken});
  HttpServerDef httpDef;
  httpDef.port = kPort;
  httpDef.listen = false;
  HttpServer http(httpDef, [&](const HttpRequest& request) {
    HttpResponse response = studio.handle(request);
    check(request, response, place.saved);
    return response;
  });
  const std::map<std::string, double> defines = model.defineValues();
  const nlohmann::json limits = model.state()["limits"];
  http.answerBytes(std::string_view(reinterpret_cast<const char*>(data), size));
  // A slider or limit a request moved: the growth it asked for, on this thread.
  if (model.defineValues() != defines || model.state()["limits"] != limits) model.regrow();
  return 0;
}
