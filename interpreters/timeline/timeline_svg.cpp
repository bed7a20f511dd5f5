#include "interpreters/timeline/timeline_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "interpreters/output_file.h"
#include "interpreters/timeline/timeline_layout.h"

namespace ontogen {

namespace {
std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
  return buffer;
}

std::string hex(const std::array<uint8_t, 3>& rgb) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return buffer;
}

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}
}  // namespace

std::string timelineSvg(const Timeline& timeline, const std::string& title) {
  using L = TimelineLayout;
  const TimelineLayout layout(timeline);
  auto colour = [&](const std::string& label) { return hex(L::colours()[layout.colourIndex.at(label)]); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(layout.width) << "\" height=\""
      << number(layout.height) << "\" viewBox=\"0 0 " << number(layout.width) << " " << number(layout.height)
      << "\" font-family=\"sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << L::kLeft << "\" y=\"22\" font-size=\"15\">" << escape(title) << ": time-state diagram, "
      << timeline.rows.size() << " cells";
  if (timeline.omitted) svg << " (" << timeline.omitted << " more not drawn)";
  svg << "</text>\n";
  // Legend, right-aligned on the title line.
  double legendX = layout.width - L::kRight;
  for (auto it = layout.labels.rbegin(); it != layout.labels.rend(); ++it) {
    legendX -= 14 + 7.0 * static_cast<double>(it->size()) + 10;
    svg << "<rect class=\"legend\" x=\"" << number(legendX) << "\" y=\"12\" width=\"10\" height=\"10\" fill=\""
        << colour(*it) << "\"/><text x=\"" << number(legendX + 14) << "\" y=\"21\" font-size=\"11\">"
        << escape(*it) << "</text>\n";
  }
  // Bars; a system's pool hangs under its row with a bracket line at its indent.
  for (size_t i = 0; i < timeline.rows.size(); ++i) {
    const TimelineRow& row = timeline.rows[i];
    const double y = layout.rowY(i), h = layout.rowHeight;
    const double x0 = layout.x(row.born), x1 = layout.x(row.gone);
    svg << "<rect class=\"cell\" data-label=\"" << escape(row.label) << "\" x=\"" << number(x0) << "\" y=\""
        << number(y + h * 0.1) << "\" width=\"" << number(std::max(x1 - x0, 0.5)) << "\" height=\""
        << number(h * 0.8) << "\" fill=\"" << colour(row.label) << "\"";
    if (row.system) svg << " stroke=\"black\" stroke-width=\"0.6\"";
    svg << "/>\n";
    const double bracket = L::kLeft - 4 - L::kIndent * row.depth;
    if (row.depth > 0)
      svg << "<line x1=\"" << number(bracket) << "\" y1=\"" << number(y) << "\" x2=\"" << number(bracket)
          << "\" y2=\"" << number(y + h) << "\" stroke=\"#555\" stroke-width=\"1.5\"/>\n";
    if (h >= 9)
      svg << "<text x=\"" << number(L::kLeft - 6 - L::kIndent * 3) << "\" y=\"" << number(y + h * 0.8)
          << "\" font-size=\"" << number(h * 0.75) << "\" text-anchor=\"end\">" << escape(row.label) << "</text>\n";
  }
  // Time axis.
  const double axisY = layout.axisY();
  svg << "<line x1=\"" << L::kLeft << "\" y1=\"" << number(axisY) << "\" x2=\"" << L::kLeft + L::kPlotWidth
      << "\" y2=\"" << number(axisY) << "\" stroke=\"black\"/>\n";
  for (double t : layout.ticks) {
    std::string text = number(t);
    if (text.size() > 3 && text.compare(text.size() - 3, 3, ".00") == 0) text.resize(text.size() - 3);
    svg << "<line x1=\"" << number(layout.x(t)) << "\" y1=\"" << number(axisY) << "\" x2=\"" << number(layout.x(t))
        << "\" y2=\"" << number(axisY + 5) << "\" stroke=\"black\"/><text x=\"" << number(layout.x(t)) << "\" y=\""
        << number(axisY + 18) << "\" font-size=\"11\" text-anchor=\"middle\">" << text << "</text>\n";
  }
  svg << "<text x=\"" << L::kLeft + L::kPlotWidth / 2 << "\" y=\"" << number(axisY + 36)
      << "\" font-size=\"12\" text-anchor=\"middle\">time</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

void writeTimelineSvg(const std::filesystem::path& path, const Timeline& timeline, const std::string& title) {
  const std::string text = timelineSvg(timeline, title);
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace ontogen
