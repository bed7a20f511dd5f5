#pragma once
// Where a time-state diagram's parts go, shared by its SVG and PNG pictures: the plot
// area, the height of a row, the x of a time, the colour of each label (twelve colours
// that stay apart, in order of first appearance) and the time ticks.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "interpreters/timeline/timeline_recorder.h"

namespace ontogen {

struct TimelineLayout {
  explicit TimelineLayout(const Timeline& timeline);

  static constexpr double kLeft = 60, kRight = 40, kTop = 50, kBottom = 50, kPlotWidth = 900, kIndent = 10;
  double width = 0, height = 0;
  double rowHeight = 0;
  double plotHeight = 0;
  std::vector<std::string> labels;        ///< in order of first appearance
  std::map<std::string, int> colourIndex;  ///< label -> index into colours()
  std::vector<double> ticks;              ///< times of the axis ticks

  double x(double t) const;
  double rowY(size_t row) const { return kTop + rowHeight * static_cast<double>(row); }
  double axisY() const { return kTop + plotHeight + 6; }

  static const std::array<std::array<uint8_t, 3>, 12>& colours();

 private:
  double start_ = 0, span_ = 1;
};

}  // namespace ontogen
