#include "studio/gallery_grower.h"

#include <utility>

namespace ontogen::studio {

GalleryGrower::GalleryGrower(Gallery& gallery) : gallery_(gallery), thread_([this] { growInTurn(); }) {}

GalleryGrower::~GalleryGrower() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    cancel_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void GalleryGrower::wake() {
  // Called with the lock held. A variant of a replaced generation stops growing: its
  // picture would be dropped (Gallery::keep).
  if (growingEpoch_ && *growingEpoch_ != gallery_.epoch()) cancel_ = true;
  changed_.notify_all();
}

bool GalleryGrower::waitGrown(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout, [this] { return !gallery_.nextTask().has_value(); });
}

void GalleryGrower::growInTurn() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    std::optional<GalleryTask> task;
    changed_.wait(lock, [&] { return stopping_ || (task = gallery_.nextTask()).has_value(); });
    if (stopping_) return;
    growingEpoch_ = task->epoch;
    cancel_ = false;
    lock.unlock();
    // The gallery may be read and made anew meanwhile: grow() reads only the task and
    // the gallery's settings.
    GalleryPicture picture = gallery_.grow(*task, &cancel_);
    lock.lock();
    growingEpoch_.reset();
    // Cancelled as the grower ends: the picture is no outcome of the variant or probe, and
    // the gallery, which outlives the grower, grows it again under the next one.
    if (stopping_) return;
    gallery_.keep(*task, std::move(picture));
    changed_.notify_all();
  }
}

}  // namespace ontogen::studio
