#include "interpreters/timeline/timeline_layout.h"

#include <algorithm>
#include <cmath>

namespace ontogen {

namespace {
// A tick spacing of 1, 2 or 5 times a power of ten giving about eight ticks.
double tickStep(double span) {
  if (!(span > 0)) return 1;
  const double raw = span / 8;
  const double power = std::pow(10, std::floor(std::log10(raw)));
  for (double factor : {1.0, 2.0, 5.0})
    if (raw <= factor * power) return factor * power;
  return 10 * power;
}
}  // namespace

const std::array<std::array<uint8_t, 3>, 12>& TimelineLayout::colours() {
  static const std::array<std::array<uint8_t, 3>, 12> kColours = {{{0x4e, 0x79, 0xa7},
                                                                   {0xf2, 0x8e, 0x2b},
                                                                   {0x59, 0xa1, 0x4f},
                                                                   {0xe1, 0x57, 0x59},
                                                                   {0x76, 0xb7, 0xb2},
                                                                   {0xed, 0xc9, 0x48},
                                                                   {0xb0, 0x7a, 0xa1},
                                                                   {0xff, 0x9d, 0xa7},
                                                                   {0x9c, 0x75, 0x5f},
                                                                   {0xba, 0xb0, 0xac},
                                                                   {0x1b, 0x9e, 0x77},
                                                                   {0x75, 0x70, 0xb3}}};
  return kColours;
}

TimelineLayout::TimelineLayout(const Timeline& timeline) {
  const size_t rows = std::max<size_t>(timeline.rows.size(), 1);
  rowHeight = std::clamp(640.0 / static_cast<double>(rows), 1.0, 14.0);
  plotHeight = rowHeight * static_cast<double>(rows);
  width = kLeft + kPlotWidth + kRight;
  height = kTop + plotHeight + kBottom;
  start_ = timeline.start;
  span_ = std::max(timeline.end - timeline.start, 1e-9);
  for (const TimelineRow& row : timeline.rows)
    if (!colourIndex.count(row.label)) {
      colourIndex[row.label] = static_cast<int>(labels.size() % colours().size());
      labels.push_back(row.label);
    }
  const double step = tickStep(span_);
  for (double t = std::ceil(timeline.start / step) * step; t <= timeline.end + step * 1e-6; t += step)
    ticks.push_back(t);
}

double TimelineLayout::x(double t) const {
  return kLeft + (std::clamp(t, start_, start_ + span_) - start_) / span_ * kPlotWidth;
}

}  // namespace ontogen
