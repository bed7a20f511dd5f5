#pragma once

#include <chrono>
#include <optional>
#include <string>

namespace ontogen::app {

/// A one-line progress bar on stderr, redrawn in place with a carriage return.
class ProgressBar {
 public:
  /// Drawn when `show` says so, else (empty) only when stderr is a terminal: under
  /// mpirun stderr is a pipe to the launcher even when the user watches it, so a sweep
  /// across ranks asks for its bar with --progress.
  explicit ProgressBar(std::string label, std::optional<bool> show = {});
  ~ProgressBar();
  /// done of total units; redraws at most every 100 ms.
  void update(long done, long total);
  /// The same with a note after the count ("2 failed, 40 s left").
  void update(long done, long total, const std::string& note);
  /// Stops drawing (a rank other than the first of a sweep across machines).
  void disable() { enabled_ = false; }
  void finish();

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace ontogen::app
