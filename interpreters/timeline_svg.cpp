#include "interpreters/timeline_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "interpreters/output_file.h"

namespace ontogen {

namespace {
// Twelve colours that stay apart from each other, for labels in order of appearance.
constexpr const char* kColours[] = {"#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#76b7b2", "#edc948",
                                    "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac", "#1b9e77", "#7570b3"};

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
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

std::string timelineSvg(const Timeline& timeline, const std::string& title) {
  constexpr double kLeft = 60, kRight = 40, kTop = 50, kBottom = 50, kPlotWidth = 900, kIndent = 10;
  const size_t rows = std::max<size_t>(timeline.rows.size(), 1);
  const double rowHeight = std::clamp(640.0 / static_cast<double>(rows), 1.0, 14.0);
  const double plotHeight = rowHeight * static_cast<double>(rows);
  const double width = kLeft + kPlotWidth + kRight, height = kTop + plotHeight + kBottom;
  const double span = std::max(timeline.end - timeline.start, 1e-9);
  auto x = [&](double t) { return kLeft + (std::clamp(t, timeline.start, timeline.end) - timeline.start) / span * kPlotWidth; };

  std::map<std::string, std::string> colour;
  std::vector<std::string> order;
  for (const TimelineRow& row : timeline.rows)
    if (!colour.count(row.label)) {
      colour[row.label] = kColours[order.size() % std::size(kColours)];
      order.push_back(row.label);
    }

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(width) << "\" height=\"" << number(height)
      << "\" viewBox=\"0 0 " << number(width) << " " << number(height) << "\" font-family=\"sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"15\">" << escape(title) << ": time-state diagram, "
      << timeline.rows.size() << " cells";
  if (timeline.omitted) svg << " (" << timeline.omitted << " more not drawn)";
  svg << "</text>\n";
  // Legend, right-aligned on the title line.
  double legendX = width - kRight;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    legendX -= 14 + 7.0 * static_cast<double>(it->size()) + 10;
    svg << "<rect class=\"legend\" x=\"" << number(legendX) << "\" y=\"12\" width=\"10\" height=\"10\" fill=\""
        << colour[*it] << "\"/><text x=\"" << number(legendX + 14) << "\" y=\"21\" font-size=\"11\">" << escape(*it)
        << "</text>\n";
  }
  // Bars; a system's pool hangs under its row with a bracket line at its indent.
  for (size_t i = 0; i < timeline.rows.size(); ++i) {
    const TimelineRow& row = timeline.rows[i];
    const double y = kTop + rowHeight * static_cast<double>(i);
    const double indent = kIndent * row.depth;
    const double x0 = x(row.born), x1 = x(row.gone);
    svg << "<rect class=\"cell\" data-label=\"" << escape(row.label) << "\" x=\"" << number(x0) << "\" y=\""
        << number(y + rowHeight * 0.1) << "\" width=\"" << number(std::max(x1 - x0, 0.5)) << "\" height=\""
        << number(rowHeight * 0.8) << "\" fill=\"" << colour[row.label] << "\"";
    if (row.system) svg << " stroke=\"black\" stroke-width=\"0.6\"";
    svg << "/>\n";
    if (row.depth > 0)
      svg << "<line x1=\"" << number(kLeft - 4 - indent) << "\" y1=\"" << number(y) << "\" x2=\""
          << number(kLeft - 4 - indent) << "\" y2=\"" << number(y + rowHeight) << "\" stroke=\"#555\" stroke-width=\"1.5\"/>\n";
    if (rowHeight >= 9)
      svg << "<text x=\"" << number(kLeft - 6 - kIndent * 3) << "\" y=\"" << number(y + rowHeight * 0.8)
          << "\" font-size=\"" << number(rowHeight * 0.75) << "\" text-anchor=\"end\">" << escape(row.label)
          << "</text>\n";
  }
  // Time axis.
  const double axisY = kTop + plotHeight + 6;
  svg << "<line x1=\"" << kLeft << "\" y1=\"" << number(axisY) << "\" x2=\"" << kLeft + kPlotWidth << "\" y2=\""
      << number(axisY) << "\" stroke=\"black\"/>\n";
  const double step = tickStep(span);
  for (double t = std::ceil(timeline.start / step) * step; t <= timeline.end + step * 1e-6; t += step) {
    svg << "<line x1=\"" << number(x(t)) << "\" y1=\"" << number(axisY) << "\" x2=\"" << number(x(t)) << "\" y2=\""
        << number(axisY + 5) << "\" stroke=\"black\"/><text x=\"" << number(x(t)) << "\" y=\"" << number(axisY + 18)
        << "\" font-size=\"11\" text-anchor=\"middle\">" << number(t).substr(0, number(t).find(".00")) << "</text>\n";
  }
  svg << "<text x=\"" << kLeft + kPlotWidth / 2 << "\" y=\"" << number(axisY + 36)
      << "\" font-size=\"12\" text-anchor=\"middle\">time</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

void writeTimelineSvg(const std::filesystem::path& path, const Timeline& timeline, const std::string& title) {
  const std::string text = timelineSvg(timeline, title);
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace ontogen
