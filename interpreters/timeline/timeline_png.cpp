#include "interpreters/timeline/timeline_png.h"

#include <algorithm>
#include <cmath>

#include "interpreters/formats/png_writer.h"
#include "interpreters/output_file.h"
#include "interpreters/timeline/timeline_layout.h"

namespace ontogen {

namespace {
void fill(Image& image, double x0, double y0, double x1, double y1, const std::array<uint8_t, 3>& rgb) {
  const int left = std::max(0, static_cast<int>(std::floor(x0)));
  const int right = std::min(image.width, static_cast<int>(std::ceil(x1)));
  const int top = std::max(0, static_cast<int>(std::floor(y0)));
  const int bottom = std::min(image.height, static_cast<int>(std::ceil(y1)));
  for (int y = top; y < bottom; ++y)
    for (int x = left; x < right; ++x) std::copy(rgb.begin(), rgb.end(), image.rgb.begin() + (y * image.width + x) * 3);
}
}  // namespace

Image timelineImage(const Timeline& timeline) {
  using L = TimelineLayout;
  const TimelineLayout layout(timeline);
  Image image;
  image.width = static_cast<int>(std::ceil(layout.width));
  image.height = static_cast<int>(std::ceil(layout.height));
  image.rgb.assign(static_cast<size_t>(image.width) * image.height * 3, 255);
  const std::array<uint8_t, 3> black{0, 0, 0}, grey{85, 85, 85};
  for (size_t i = 0; i < timeline.rows.size(); ++i) {
    const TimelineRow& row = timeline.rows[i];
    const double y = layout.rowY(i), h = layout.rowHeight;
    const double x0 = layout.x(row.born), x1 = std::max(layout.x(row.gone), x0 + 1);
    // Bars keep a gap between rows when rows are tall enough to show one.
    const double inset = h >= 3 ? h * 0.1 : 0;
    fill(image, x0, y + inset, x1, y + h - inset, L::colours()[layout.colourIndex.at(row.label)]);
    if (row.depth > 0) {
      const double bracket = L::kLeft - 4 - L::kIndent * row.depth;
      fill(image, bracket - 1, y, bracket + 1, y + h, grey);
    }
  }
  const double axisY = layout.axisY();
  fill(image, L::kLeft, axisY, L::kLeft + L::kPlotWidth, axisY + 1, black);
  for (double t : layout.ticks) fill(image, layout.x(t) - 0.5, axisY, layout.x(t) + 0.5, axisY + 5, black);
  return image;
}

void writeTimelinePng(const std::filesystem::path& path, const Timeline& timeline) {
  const Image image = timelineImage(timeline);
  writeFileAtomically(path, [&](std::ostream& out) { writePng(image, out); });
}

}  // namespace ontogen
