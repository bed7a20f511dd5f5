#pragma once
// Grows a gallery's variants on a thread of its own, one after the other, so that a
// request that makes a generation (POST /api/gallery, /api/breed, /api/gallery/restart)
// is answered at once and the page shows each picture as it comes. A generation made
// while another grows replaces it: the variant growing is cancelled and its picture
// dropped.
//
// The gallery is shared: whoever reads or changes it holds lock(), and calls wake()
// after making a generation.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>

#include "studio/gallery.h"

namespace ontogen::studio {

class GalleryGrower {
 public:
  /// Starts the thread; it grows whatever the gallery has not grown yet.
  explicit GalleryGrower(Gallery& gallery);
  /// Cancels the variant growing and waits for the thread.
  ~GalleryGrower();
  GalleryGrower(const GalleryGrower&) = delete;
  GalleryGrower& operator=(const GalleryGrower&) = delete;

  /// Held to read or change the gallery.
  [[nodiscard]] std::unique_lock<std::mutex> lock() { return std::unique_lock<std::mutex>(mutex_); }
  /// After a generation was made (with lock() held): grows it, cancelling the growth of
  /// the one it replaced.
  void wake();
  /// Waits until every variant of the gallery's generation is grown, or the time is up
  /// (false). Takes the lock itself.
  bool waitGrown(std::chrono::milliseconds timeout);

 private:
  void growInTurn();

  Gallery& gallery_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::atomic<bool> cancel_{false};    // stops the variant growing (Run's WorldLimits::cancel)
  std::optional<uint64_t> growingEpoch_;  // the generation of the variant growing, if any
  bool stopping_ = false;
  std::thread thread_;  // last: started once the rest is ready
};

}  // namespace ontogen::studio
