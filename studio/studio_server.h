#pragma once
// What the studio's page can ask of it, over HTTP (studio/http_server.h):
//
//   GET  /, /studio.js, /studio.css   the page (studio/studio_assets.h)
//   GET  /api/state                   versions, diagnostics, defines, times, source, growth, limits (JSON)
//   GET  /api/events                  the state again at each change, as server-sent events
//   GET  /model.glb                   the last model that grew, as `ontogen run --format glb` writes it
//   GET  /api/notes                   the music set's notes, in seconds (JSON)
//   POST /api/define                  {"name": N, "value": V}: move a slider (within its range) and
//                                     grow again; answers the state
//   POST /api/stop                    cancel the growth at hand; the last model stays
//   POST /api/limits                  {"maxCells": N, "maxMemoryMiB": M}: the interactive limits; grows again
//   GET  /api/gallery                 the evolution gallery (JSON), made at the first ask
//   GET  /gallery/K.png               the picture of variant K
//   POST /api/breed                   {"picked": [K, ...]}: the next generation
//   POST /api/save                    {"index": K}: write variant K as a program; answers its path
//   POST /api/gallery/restart         a new gallery from the program with the sliders' values
//
// Errors are JSON {"error": message} with status 400 (a bad request) or 422 (a request the
// model cannot follow).

#include <cstdint>
#include <mutex>
#include <string>

#include "studio/gallery.h"
#include "studio/http_server.h"
#include "studio/studio_model.h"

namespace ontogen::studio {

class StudioServer {
 public:
  StudioServer(StudioModel& model, Gallery& gallery) : model_(model), gallery_(gallery) {}

  /// Answers a request; called on many threads at once. The model grows on its own
  /// thread (StudioModel::start()); the gallery answers one request at a time.
  HttpResponse handle(const HttpRequest& request);
  /// Called now and then: asks the model to grow again when its file changed.
  void idle();

 private:
  void restartGallery();
  HttpResponse events();

  StudioModel& model_;
  Gallery& gallery_;
  std::string galleryText_;  // the model text the gallery started from
  std::mutex galleryMutex_;  // the gallery and galleryText_
};

}  // namespace ontogen::studio
