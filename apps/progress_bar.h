#pragma once

#include <chrono>
#include <string>

namespace ontogen::app {

/// A one-line progress bar on stderr, drawn only when stderr is a terminal.
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
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
