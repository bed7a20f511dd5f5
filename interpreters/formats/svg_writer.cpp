#include "interpreters/formats/svg_writer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace ontogen {

namespace {

// Sides of the polygon a disc's outline is drawn with: at 64 the polygon departs from
// the ellipse by 0.12% of its radius, under a pixel for any disc inside the picture.
constexpr int kOutlineSides = 64;
// Below this extent (model units) a drawing is a point: it is given a unit scale.
constexpr double kTinyExtent = 1e-12;

constexpr const char* kCylinderColour = "#666666";
constexpr const char* kDiscColour = "#d9d9d9";
constexpr const char* kSphereColour = "#999999";

/// Fixed-point text with at most `decimals` digits after the point, no trailing zeros,
/// and never "-0": the same number always gives the same text, whatever the locale.
class NumberFormat {
 public:
  explicit NumberFormat(int decimals) : decimals_(decimals) {}

  std::string operator()(double value) const {
    char buffer[64];
    auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value,
                                      std::chars_format::fixed, decimals_);
    if (error != std::errc()) return "0";  // only for absurd magnitudes
    std::string text(buffer, end);
    if (text.find('.') != std::string::npos) {
      while (text.back() == '0') text.pop_back();
      if (text.back() == '.') text.pop_back();
    }
    if (text == "-0") text = "0";
    return text;
  }

 private:
  int decimals_;
};

/// The extent in x and y of what is drawn, in model units.
struct Extent {
  double minX = 0, maxX = 0, minY = 0, maxY = 0;
  bool empty = true;

  void add(double x, double y, double halfX, double halfY) {
    if (empty) {
      minX = x - halfX;
      maxX = x + halfX;
      minY = y - halfY;
      maxY = y + halfY;
      empty = false;
      return;
    }
    minX = std::min(minX, x - halfX);
    maxX = std::max(maxX, x + halfX);
    minY = std::min(minY, y - halfY);
    maxY = std::max(maxY, y + halfY);
  }
};

Extent extentOf(const Geometry& geometry) {
  Extent extent;
  for (const Segment& s : geometry.segments()) {
    extent.add(s.start.x, s.start.y, 0, 0);
    extent.add(s.end.x, s.end.y, 0, 0);
  }
  for (const CylinderPrimitive& c : geometry.cylinders()) {
    extent.add(c.start.x, c.start.y, c.radius, c.radius);
    extent.add(c.end.x, c.end.y, c.radius, c.radius);
  }
  for (const DiscPrimitive& d : geometry.discs()) {
    // The projected rim is an ellipse; its half-extent along x is outer * |(a.x, b.x)|.
    extent.add(d.centre.x, d.centre.y, d.outer * std::hypot(d.axisA.x, d.axisB.x),
               d.outer * std::hypot(d.axisA.y, d.axisB.y));
  }
  for (const SpherePrimitive& s : geometry.spheres()) {
    extent.add(s.centre.x, s.centre.y, s.radius, s.radius);
  }
  return extent;
}

/// Model x-y to picture coordinates: scaled, y flipped, inside the margin.
struct Projection {
  double minX = 0;
  double maxY = 0;
  double scale = 1;
  double margin = 0;

  glm::dvec2 operator()(const glm::dvec3& p) const {
    return {(p.x - minX) * scale + margin, (maxY - p.y) * scale + margin};
  }
};

enum class Kind { Disc, Cylinder, Sphere, Segment };

struct Item {
  double depth;  ///< z of the primitive's middle; smaller is farther from the viewer
  Kind kind;
  std::size_t index;
};

std::vector<Item> paintingOrder(const Geometry& geometry) {
  std::vector<Item> items;
  items.reserve(geometry.discs().size() + geometry.cylinders().size() +
                geometry.spheres().size() + geometry.segments().size());
  for (std::size_t i = 0; i < geometry.discs().size(); ++i) {
    items.push_back({geometry.discs()[i].centre.z, Kind::Disc, i});
  }
  for (std::size_t i = 0; i < geometry.cylinders().size(); ++i) {
    const CylinderPrimitive& c = geometry.cylinders()[i];
    items.push_back({0.5 * (c.start.z + c.end.z), Kind::Cylinder, i});
  }
  for (std::size_t i = 0; i < geometry.spheres().size(); ++i) {
    items.push_back({geometry.spheres()[i].centre.z, Kind::Sphere, i});
  }
  for (std::size_t i = 0; i < geometry.segments().size(); ++i) {
    const Segment& s = geometry.segments()[i];
    items.push_back({0.5 * (s.start.z + s.end.z), Kind::Segment, i});
  }
  std::stable_sort(items.begin(), items.end(),
                   [](const Item& a, const Item& b) { return a.depth < b.depth; });
  return items;
}

}  // namespace

void checkSvgOptions(const SvgOptions& o) {
  if (!(o.hairline > 0) || !std::isfinite(o.hairline)) {
    throw std::invalid_argument("SvgOptions::hairline must be > 0");
  }
  if (!(o.margin >= o.hairline) || !std::isfinite(o.margin)) {
    throw std::invalid_argument("SvgOptions::margin must be >= hairline");
  }
  if (!(o.size > 2 * o.margin) || !std::isfinite(o.size)) {
    throw std::invalid_argument("SvgOptions::size must exceed twice the margin");
  }
  if (o.decimals < 0 || o.decimals > 6) {
    throw std::invalid_argument("SvgOptions::decimals must be in 0..6");
  }
}

void writeSvg(const Geometry& geometry, std::ostream& out, const SvgOptions& options) {
  checkSvgOptions(options);
  const NumberFormat number(options.decimals);
  const Extent extent = extentOf(geometry);

  Projection project;
  project.margin = options.margin;
  double spanX = 0;
  double spanY = 0;
  if (!extent.empty) {
    spanX = extent.maxX - extent.minX;
    spanY = extent.maxY - extent.minY;
    project.minX = extent.minX;
    project.maxY = extent.maxY;
    double span = std::max(spanX, spanY);
    if (span > kTinyExtent) project.scale = (options.size - 2 * options.margin) / span;
  }
  const std::string width = number(spanX * project.scale + 2 * options.margin);
  const std::string height = number(spanY * project.scale + 2 * options.margin);
  const std::string hairline = number(options.hairline);

  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << width
      << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << ' ' << height << "\">\n";
  char scaleText[32];
  auto scaleEnd = std::to_chars(scaleText, scaleText + sizeof scaleText, project.scale,
                                std::chars_format::general, 6).ptr;
  out << "<!-- ontogen geometry: orthographic view along -z of the x-y plane, y up; "
      << "1 model unit = " << std::string_view(scaleText, scaleEnd - scaleText) << " px; "
      << geometry.segments().size() << " lines, " << geometry.cylinders().size()
      << " cylinders, " << geometry.discs().size() << " discs, " << geometry.spheres().size()
      << " spheres -->\n";
  out << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height
      << "\" fill=\"white\"/>\n";
  out << "<g fill=\"none\" stroke=\"black\" stroke-width=\"" << hairline
      << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";

  auto point = [&](const glm::dvec3& p) {
    glm::dvec2 q = project(p);
    return number(q.x) + ' ' + number(q.y);
  };
  for (const Item& item : paintingOrder(geometry)) {
    switch (item.kind) {
      case Kind::Segment: {
        const Segment& s = geometry.segments()[item.index];
        glm::dvec2 a = project(s.start);
        glm::dvec2 b = project(s.end);
        out << "<line x1=\"" << number(a.x) << "\" y1=\"" << number(a.y) << "\" x2=\""
            << number(b.x) << "\" y2=\"" << number(b.y) << "\"/>\n";
        break;
      }
      case Kind::Cylinder: {
        const CylinderPrimitive& c = geometry.cylinders()[item.index];
        glm::dvec2 a = project(c.start);
        glm::dvec2 b = project(c.end);
        double stroke = std::max(2 * c.radius * project.scale, options.hairline);
        out << "<line x1=\"" << number(a.x) << "\" y1=\"" << number(a.y) << "\" x2=\""
            << number(b.x) << "\" y2=\"" << number(b.y) << "\" stroke=\"" << kCylinderColour
            << "\" stroke-width=\"" << number(stroke) << "\" stroke-linecap=\"butt\"/>\n";
        break;
      }
      case Kind::Disc: {
        const DiscPrimitive& d = geometry.discs()[item.index];
        out << "<path d=\"";
        for (double radius : {d.outer, d.inner}) {
          if (radius <= 0) continue;
          for (int i = 0; i < kOutlineSides; ++i) {
            double angle = 2 * std::numbers::pi * i / kOutlineSides;
            glm::dvec3 p = d.centre + radius * (std::cos(angle) * d.axisA +
                                                std::sin(angle) * d.axisB);
            out << (i == 0 ? (radius == d.outer ? "M " : " M ") : (i == 1 ? " L " : " "))
                << point(p);
          }
          out << " Z";
        }
        out << "\" fill=\"" << kDiscColour << "\" fill-rule=\"evenodd\"/>\n";
        break;
      }
      case Kind::Sphere: {
        const SpherePrimitive& s = geometry.spheres()[item.index];
        glm::dvec2 c = project(s.centre);
        out << "<circle cx=\"" << number(c.x) << "\" cy=\"" << number(c.y) << "\" r=\""
            << number(s.radius * project.scale) << "\" fill=\"" << kSphereColour << "\"/>\n";
        break;
      }
    }
  }
  out << "</g>\n</svg>\n";
}

}  // namespace ontogen
