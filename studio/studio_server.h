#pragma once
// What the studio's page can ask of it, over HTTP (studio/http_server.h):
//
//   GET  /, /studio.js, /studio.css   the page (studio/studio_assets.h), the run's token written in
//   GET  /api/state                   versions, diagnostics, defines, times, source, growth, limits (JSON)
//   GET  /api/events                  the state again at each change, as server-sent events
//   GET  /model.glb                   the last model that grew, as `ontogen run --format glb` writes it
//   GET  /api/notes                   the music set's notes, in seconds (JSON)
//   GET  /api/gallery                 the evolution gallery as it stands (JSON; generation 0 before one is made)
//   GET  /gallery/K.png               the picture of variant K
//   GET  /model/picture/K.png         the image set's picture of the model's frame K
//   POST /api/define                  {"name": N, "value": V}: move a slider (within its range) and
//                                     grow again; answers the state
//   POST /api/define/write            {"name": N}: write the slider's value into the file (as its
//                                     number in each `#define N`); answers {"path", "state"}
//   POST /api/define/drop             {"name": N}: drop the slider's value, the file's is in effect again
//   POST /api/stop                    cancel the growth at hand; the last model stays
//   POST /api/limits                  {"maxCells": N, "maxMemoryMiB": M}: the interactive limits (of the
//                                     model and the gallery's variants to come); grows again
//   POST /api/gallery                 {}: the gallery, made at the first ask and again when the program changed
//   POST /api/breed                   {"picked": [K, ...]}: the next generation (a variant need not be
//                                     grown to be picked)
//   POST /api/save                    {"index": K}: write variant K as a program under a name the
//                                     studio makes (no name or path is taken); answers its path
//   POST /api/gallery/restart         a new gallery from the program with the sliders' values
//
// The three that make a generation answer at once, before its variants grow: they grow on
// a thread of their own (studio/gallery_grower.h), and /api/gallery tells how far
// ("grown", "growing"), while the model, its page and the gallery's own requests go on.
//
// Every request must be addressed to the studio (Host 127.0.0.1:PORT or localhost:PORT),
// and every POST must come from its page (Origin) with the run's token (X-Ontogen-Token),
// or it is refused with 403 (studio/request_guard.h). Other errors are JSON {"error":
// message} with status 400 (a bad request) or 422 (a request the model cannot follow).

#include <chrono>
#include <cstdint>
#include <string>

#include "studio/gallery.h"
#include "studio/gallery_grower.h"
#include "studio/http_server.h"
#include "studio/studio_model.h"

namespace ontogen::studio {

struct StudioServerDef {
  /// The token the page's changes carry (X-Ontogen-Token); empty: a new random one
  /// (randomToken(), 256 bits), as each run of the studio makes.
  std::string token;
};

class StudioServer {
 public:
  /// Throws std::runtime_error when no random token can be made.
  StudioServer(StudioModel& model, Gallery& gallery, StudioServerDef def = {});

  /// The run's token, which the page served at / holds.
  const std::string& token() const { return token_; }

  /// Answers a request; called on many threads at once. The model grows on its own
  /// thread (StudioModel::start()), the gallery's variants on another.
  HttpResponse handle(const HttpRequest& request);
  /// Waits until the gallery's generation is grown, or the time is up (false).
  bool waitForGallery(std::chrono::milliseconds timeout) { return grower_.waitGrown(timeout); }
  /// Called now and then: asks the model to grow again when its file changed.
  void idle();

 private:
  void restartGallery();
  HttpResponse events();

  StudioModel& model_;
  Gallery& gallery_;
  std::string token_;
  std::string page_;  // index.html with the token written in
  std::string galleryText_;  // the model text the gallery started from; under grower_.lock()
  GalleryGrower grower_;     // grows the gallery's variants; its lock guards the gallery
};

}  // namespace ontogen::studio
