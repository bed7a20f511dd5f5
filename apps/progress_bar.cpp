#include "apps/progress_bar.h"

#include <unistd.h>

#include <cstdio>

namespace ontogen::app {

ProgressBar::ProgressBar(std::string label, std::optional<bool> show)
    : label_(std::move(label)), enabled_(show.value_or(isatty(STDERR_FILENO) == 1)) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(long done, long total) { update(done, total, std::string()); }

void ProgressBar::update(long done, long total, const std::string& note) {
  if (!enabled_ || total <= 0) return;
  auto now = std::chrono::steady_clock::now();
  if (drawn_ && done < total && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  constexpr int kWidth = 30;
  int filled = static_cast<int>(kWidth * done / total);
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  // A note is padded so that a shorter one overwrites a longer one before it.
  std::string tail = note.empty() ? std::string() : ", " + note;
  if (!tail.empty() && tail.size() < 28) tail.resize(28, ' ');
  std::fprintf(stderr, "\r%s [%s] %ld/%ld%s", label_.c_str(), bar.c_str(), done, total, tail.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace ontogen::app
