#include "interpreters/text/trace_set.h"

#include <cstdio>

#include "interpreters/output_file.h"

namespace ontogen {

void TraceSet::beginFrame(const FrameTarget& target) {
  target_ = target;
  text_.clear();
}

void TraceSet::execute(std::string_view command, std::span<const double> args) {
  if (!text_.empty()) text_ += ' ';
  text_.append(command);
  if (args.empty()) return;
  text_ += '(';
  for (size_t i = 0; i < args.size(); ++i) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", args[i] == 0 ? 0.0 : args[i]);
    if (i) text_ += ", ";
    text_ += buffer;
  }
  text_ += ')';
}

std::vector<std::filesystem::path> TraceSet::endFrame() {
  std::string name = target_.stem;
  if (target_.frameCount > 1) {
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%04d", target_.frame);
    name += suffix;
  }
  std::filesystem::path path = target_.directory / (name + ".txt");
  writeFileAtomically(path, [&](std::ostream& out) { out << text_ << '\n'; });
  return {path};
}

}  // namespace ontogen
