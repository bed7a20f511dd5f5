#pragma once
// The "trace" interpretation set: writes the instruction stream a frame produces, one
// frame per file (DIR/<stem>.txt), e.g. `F(1) +(90) F(1)`. Useful to see what another
// set would receive, and as the simplest example of a set.

#include <string>

#include "interpreters/interpretation_set.h"

namespace ontogen {

class TraceSet final : public InterpretationSet {
 public:
  std::string_view name() const override { return "trace"; }
  bool knows(std::string_view) const override { return true; }
  void beginFrame(const FrameTarget& target) override;
  void execute(std::string_view command, std::span<const double> args) override;
  std::vector<std::filesystem::path> endFrame() override;

  /// The text of the current (or last) frame.
  const std::string& text() const { return text_; }

 private:
  FrameTarget target_;
  std::string text_;
};

}  // namespace ontogen
