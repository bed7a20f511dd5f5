#include "interpreters/formats/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "interpreters/palette.h"

namespace ontogen {

namespace {

constexpr int kMaxSize = 8192;  // 3 GB of supersampled buffers at most
constexpr int kSupersample = 2;
// A model thinner than this fraction of its size along z is flat (drawn in x-y).
constexpr double kFlatRatio = 1e-9;
constexpr double kDefaultAzimuth = 30;
constexpr double kDefaultElevation = 20;
constexpr double kMaxFieldOfView = 120;  // wider is a fish-eye, not a picture of a model
// The key light: 35 degrees to the viewer's left of the view, 50 degrees above the
// horizon, so that round forms read and the shadow falls behind and to the right.
constexpr double kKeyAzimuth = -35;
constexpr double kKeyElevation = 50;
// The shadow map's side, texels: the picture's larger side, within these. 256 keeps
// a thumbnail's shadow round; 2048 (16 MB) is sharper than the soft edge anyway.
constexpr int kMinShadowMap = 256;
constexpr int kMaxShadowMap = 2048;
// Taps of the percentage-closer filter along each side: 5 x 5 give 26 shades of half
// shadow, smooth at the soft edge's width.
constexpr int kShadowTaps = 5;
// A surface seen at a grazing angle from the light would need an unbounded depth slope;
// beyond this slope (about 84 degrees) it is in its own half shadow anyway.
constexpr double kMaxDepthSlope = 10;
// The floor shows under a model seen from above it by at least this sine (3 degrees):
// seen edge-on it would be a line.
constexpr double kMinFloorSine = 0.05;
// What a sample sees: a triangle index, a line (kLine | index), or nothing.
constexpr uint32_t kNothing = 0xffffffffu;
constexpr uint32_t kLine = 0x80000000u;

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

glm::dvec3 directionOf(double azimuth, double elevation) {
  return {std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation)};
}

// A point on the canvas: x, y in samples, the depth buffer's value (larger is nearer) and
// 1 / distance for perspective-correct interpolation (1 when orthographic).
struct Projected {
  double x, y, nearness, inverseW;
};

struct Canvas {
  int width, height;
  std::vector<double> nearness;
  std::vector<uint32_t> seen;

  void plot(int x, int y, double z, uint32_t what) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    const std::size_t i = static_cast<std::size_t>(y) * width + x;
    if (z < nearness[i]) return;
    nearness[i] = z;
    seen[i] = what;
  }
};

// The camera on the supersampled canvas.
struct CanvasCamera {
  CameraView view;
  Projected project(const glm::dvec3& p) const {
    const glm::dvec3 d = p - view.centre;
    const double x = glm::dot(d, view.right), y = glm::dot(d, view.up), z = glm::dot(d, view.towardsEye);
    if (!view.perspective) return {view.cx + x * view.focal, view.cy - y * view.focal, z, 1};
    const double w = view.distance - z;
    return {view.cx + view.focal * x / w, view.cy - view.focal * y / w, 1 / w, 1 / w};
  }
  // The ray through canvas point (x, y): origin and unit direction.
  std::pair<glm::dvec3, glm::dvec3> ray(double x, double y) const {
    const double u = (x - view.cx) / view.focal, v = (view.cy - y) / view.focal;
    if (!view.perspective) {
      // From a plane in front of everything framed.
      return {view.centre + view.right * u + view.up * v + view.towardsEye * 1e6 * std::max(1.0, view.distance),
              -view.towardsEye};
    }
    return {view.eye, glm::normalize(view.right * u + view.up * v - view.towardsEye)};
  }
};

// Screen-space barycentric weights of a point in a triangle.
struct Weights {
  double w0, w1, w2;
};

template <typename Plot>
void rasterise(int width, int height, const Projected& a, const Projected& b, const Projected& c, Plot plot) {
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (!(std::abs(area) > 1e-12)) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
  const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
  const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      const double w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
      const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
      const double w2 = 1 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      plot(x, y, Weights{w0, w1, w2});
    }
  }
}

Weights weightsAt(const Projected& a, const Projected& b, const Projected& c, double px, double py) {
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  const double w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
  const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
  return {w0, w1, 1 - w0 - w1};
}

void drawLine(Canvas& canvas, const Projected& a, const Projected& b, double width, uint32_t what) {
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int steps = std::max(1, static_cast<int>(std::ceil(length * 2)));
  const int half = std::max(0, static_cast<int>(std::floor(width / 2)));
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const double px = a.x + (b.x - a.x) * t, py = a.y + (b.y - a.y) * t;
    // Nearer by a hair than a surface at the same depth, so lines on a surface show.
    const double z = a.nearness + (b.nearness - a.nearness) * t;
    const double nearer = z + std::abs(z) * 1e-7 + 1e-12;
    const int x = static_cast<int>(std::floor(px)), y = static_cast<int>(std::floor(py));
    for (int dy = -half; dy <= half; ++dy)
      for (int dx = -half; dx <= half; ++dx) canvas.plot(x + dx, y + dy, nearer, what);
  }
}

// An orthographic depth picture of the triangles seen from the key light.
class ShadowMap {
 public:
  ShadowMap(const Mesh& mesh, const Box& box, const glm::dvec3& light, double softness, int side) : light_(light) {
    const glm::dvec3 helper = std::abs(light.y) > 0.999 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
    u_ = glm::normalize(glm::cross(helper, light));
    v_ = glm::cross(light, u_);
    double uMin = std::numeric_limits<double>::infinity(), uMax = -uMin, vMin = uMin, vMax = -uMin;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                         (corner & 4) ? box.max.z : box.min.z);
      uMin = std::min(uMin, glm::dot(p, u_)), uMax = std::max(uMax, glm::dot(p, u_));
      vMin = std::min(vMin, glm::dot(p, v_)), vMax = std::max(vMax, glm::dot(p, v_));
    }
    const double span = std::max({uMax - uMin, vMax - vMin, 1e-300});
    texel_ = span / side;
    radius_ = std::max(softness, texel_);
    // Room for the filter's reach on every side.
    uMin_ = uMin - radius_ - 2 * texel_;
    vMin_ = vMin - radius_ - 2 * texel_;
    width_ = static_cast<int>(std::ceil((uMax - uMin_ + radius_ + 2 * texel_) / texel_));
    height_ = static_cast<int>(std::ceil((vMax - vMin_ + radius_ + 2 * texel_) / texel_));
    depth_.assign(static_cast<std::size_t>(width_) * height_, -std::numeric_limits<double>::infinity());
    std::vector<Projected> projected(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::dvec3& p = mesh.positions[i];
      projected[i] = {(glm::dot(p, u_) - uMin_) / texel_, (glm::dot(p, v_) - vMin_) / texel_, glm::dot(p, light), 1};
    }
    for (const Triangle& t : mesh.triangles) {
      const Projected &a = projected[t.position[0]], &b = projected[t.position[1]], &c = projected[t.position[2]];
      rasterise(width_, height_, a, b, c, [&](int x, int y, const Weights& w) {
        double& d = depth_[static_cast<std::size_t>(y) * width_ + x];
        d = std::max(d, w.w0 * a.nearness + w.w1 * b.nearness + w.w2 * c.nearness);
      });
    }
    // A summed-area table of the texels something covers: a point whose filter reaches
    // none of them (most of the floor) is in full light without a tap.
    covered_.assign(static_cast<std::size_t>(width_ + 1) * (height_ + 1), 0);
    for (int y = 0; y < height_; ++y) {
      uint32_t row = 0;
      for (int x = 0; x < width_; ++x) {
        row += depth_[static_cast<std::size_t>(y) * width_ + x] > -std::numeric_limits<double>::infinity() ? 1 : 0;
        covered_[static_cast<std::size_t>(y + 1) * (width_ + 1) + x + 1] =
            covered_[static_cast<std::size_t>(y) * (width_ + 1) + x + 1] + row;
      }
    }
  }

  /// The share of the key light reaching point p of the floor, which lies under
  /// everything the map holds: the share of the texels around p, over the soft edge's
  /// width, that nothing covers. A box filter read from the summed-area table: smooth
  /// under thin shadows (a thorn's, a rod's) where taps would alias, and four reads.
  double floorLit(const glm::dvec3& p) const {
    const double u = (glm::dot(p, u_) - uMin_) / texel_, v = (glm::dot(p, v_) - vMin_) / texel_;
    const int reach = static_cast<int>(std::ceil(radius_ / texel_));
    const double side = 2.0 * reach + 1;
    // Floor of u and v, for coordinates that may be far below zero.
    const double uFloor = std::floor(u), vFloor = std::floor(v);
    if (!(uFloor + reach >= 0 && vFloor + reach >= 0 && uFloor - reach < width_ && vFloor - reach < height_)) return 1;
    const int x0 = std::max(0, static_cast<int>(uFloor) - reach), x1 = std::min(width_, static_cast<int>(uFloor) + reach + 1);
    const int y0 = std::max(0, static_cast<int>(vFloor) - reach), y1 = std::min(height_, static_cast<int>(vFloor) + reach + 1);
    auto at = [&](int x, int y) { return covered_[static_cast<std::size_t>(y) * (width_ + 1) + x]; };
    const double covered = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
    return 1 - covered / (side * side);
  }

  /// The share of the key light reaching point p of a surface whose normal is n (unit,
  /// facing the light): 0 in full shadow, 1 in full light.
  double lit(const glm::dvec3& p, const glm::dvec3& n) const {
    // Offset along the normal by a texel and a half, against the map's own steps.
    const glm::dvec3 q = p + n * (1.5 * texel_);
    const double u = (glm::dot(q, u_) - uMin_) / texel_, v = (glm::dot(q, v_) - vMin_) / texel_;
    {
      const double reach = radius_ / texel_ + 1;
      const int x0 = std::clamp(static_cast<int>(u - reach + 1) - 1, 0, width_);
      const int x1 = std::clamp(static_cast<int>(u + reach + 1) + 1, 0, width_);
      const int y0 = std::clamp(static_cast<int>(v - reach + 1) - 1, 0, height_);
      const int y1 = std::clamp(static_cast<int>(v + reach + 1) + 1, 0, height_);
      auto at = [&](int x, int y) { return covered_[static_cast<std::size_t>(y) * (width_ + 1) + x]; };
      if (x0 >= x1 || y0 >= y1 || at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0) == 0) return 1;
    }
    const double depth = glm::dot(q, light_);
    // The receiver's plane: how its depth towards the light changes across the map, so
    // that each tap compares with the surface at the tap, not with the point itself.
    const double nz = std::max(glm::dot(n, light_), 1e-6);
    const double du = std::clamp(-glm::dot(n, u_) / nz, -kMaxDepthSlope, kMaxDepthSlope) * texel_;
    const double dv = std::clamp(-glm::dot(n, v_) / nz, -kMaxDepthSlope, kMaxDepthSlope) * texel_;
    const double bias = 1.5 * texel_;
    const double step = 2 * radius_ / texel_ / (kShadowTaps - 1);
    auto tap = [&](int i, int j) {
      const double ou = (i - (kShadowTaps - 1) / 2.0) * step, ov = (j - (kShadowTaps - 1) / 2.0) * step;
      const int x = static_cast<int>(std::floor(u + ou)), y = static_cast<int>(std::floor(v + ov));
      if (x < 0 || y < 0 || x >= width_ || y >= height_) return 1;
      return depth_[static_cast<std::size_t>(y) * width_ + x] <= depth + ou * du + ov * dv + bias ? 1 : 0;
    };
    // The corners and the centre first: when they agree, so do the taps between them,
    // but at the edges of shadows thinner than the filter (a thorn's), which it blurs away.
    constexpr int last = kShadowTaps - 1;
    const int probe = tap(0, 0) + tap(last, 0) + tap(0, last) + tap(last, last) + tap(last / 2, last / 2);
    if (probe == 0 || probe == 5) return probe / 5.0;
    int inLight = 0;
    for (int j = 0; j < kShadowTaps; ++j)
      for (int i = 0; i < kShadowTaps; ++i) inLight += tap(i, j);
    return static_cast<double>(inLight) / (kShadowTaps * kShadowTaps);
  }

 private:
  glm::dvec3 light_, u_, v_;
  double texel_ = 1, radius_ = 1, uMin_ = 0, vMin_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<double> depth_;  // towards the light: larger is nearer to it
  std::vector<uint32_t> covered_;  // (width_ + 1) x (height_ + 1), texels covered above and left
};

glm::dvec3 linear(const Color& c) {
  const Color l = linearColor(c);
  return {l.r, l.g, l.b};
}

// The palette as the look shows it, in linear light.
std::array<glm::dvec3, kPaletteSize> lookPalette(const Look& look, double shade) {
  std::array<glm::dvec3, kPaletteSize> palette;
  const glm::dvec3 background(look.background[0] / 255.0, look.background[1] / 255.0, look.background[2] / 255.0);
  for (uint32_t i = 0; i < kPaletteSize; ++i) {
    const Color c = paletteColor(i);
    glm::dvec3 display(c.r, c.g, c.b);
    const double grey = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    display = glm::dvec3(grey) + (display - glm::dvec3(grey)) * look.saturation;
    display += (background - display) * look.wash;
    display *= shade;
    palette[i] = linear(Color{std::clamp(display.x, 0.0, 1.0), std::clamp(display.y, 0.0, 1.0),
                              std::clamp(display.z, 0.0, 1.0)});
  }
  return palette;
}

// The 8-bit sRGB code of a linear value: the number of codes whose lower rounding edge
// it reaches, found by bisection in a table of those edges (a power a channel would cost
// a tenth of the picture's time).
class Encoder {
 public:
  Encoder() {
    for (int k = 0; k < 255; ++k) edges_[k] = linearFromSrgb((k + 0.5) / 255);
  }
  uint8_t operator()(double linearValue) const {
    return static_cast<uint8_t>(std::upper_bound(edges_.begin(), edges_.end(), linearValue) - edges_.begin());
  }

 private:
  std::array<double, 255> edges_{};
};

}  // namespace

glm::dvec3 CameraView::project(const glm::dvec3& point) const {
  const glm::dvec3 d = point - centre;
  const double x = glm::dot(d, right), y = glm::dot(d, up), z = glm::dot(d, towardsEye);
  if (!perspective) return {cx + x * focal, cy - y * focal, -z};
  const double w = distance - z;
  return {cx + focal * x / w, cy - focal * y / w, w};
}

void checkRenderDef(const RenderDef& def) {
  if (def.width < 1 || def.width > kMaxSize || def.height < 1 || def.height > kMaxSize) {
    throw std::invalid_argument("picture size must be in 1..8192 pixels, got " + std::to_string(def.width) + "x" +
                                std::to_string(def.height));
  }
  if (def.elevation && !(*def.elevation >= -90 && *def.elevation <= 90)) {
    throw std::invalid_argument("elevation must be in -90..90 degrees");
  }
  if (def.azimuth && !std::isfinite(*def.azimuth)) throw std::invalid_argument("azimuth must be a finite number");
  if (!(def.margin >= 0 && def.margin < 0.5)) throw std::invalid_argument("margin must be in [0, 0.5)");
  if (!(def.fieldOfView >= 0 && def.fieldOfView <= kMaxFieldOfView))
    throw std::invalid_argument("the field of view must be in 0..120 degrees");
}

uint64_t renderBytes(const RenderDef& def) {
  const uint64_t pixels = static_cast<uint64_t>(std::max(def.width, 0)) * static_cast<uint64_t>(std::max(def.height, 0));
  // The supersampled canvas: a depth (double) and what it sees (uint32_t) a sample.
  const uint64_t canvas = pixels * kSupersample * kSupersample * (sizeof(double) + sizeof(uint32_t));
  const uint64_t side = std::clamp(std::max(def.width, def.height), kMinShadowMap, kMaxShadowMap) + 8;
  // A depth and a coverage count a texel; a non-square map is up to twice as long.
  const uint64_t shadow = side * side * 2 * (sizeof(double) + sizeof(uint32_t));
  return canvas + shadow + pixels * 6;  // the picture, and about as much for its PNG
}

CameraView cameraOf(const Geometry& geometry, const RenderDef& def) {
  checkRenderDef(def);
  CameraView view;
  const Box& box = def.framing && !def.framing->empty ? *def.framing : geometry.bounds();
  view.cx = def.width * 0.5;
  view.cy = def.height * 0.5;
  if (box.empty) return view;
  const glm::dvec3 size = box.max - box.min;
  const double extent = std::max({size.x, size.y, size.z});
  view.flat = size.z <= kFlatRatio * std::max(extent, 1e-300);
  const double azimuth = radians(def.azimuth.value_or(view.flat ? 0.0 : kDefaultAzimuth));
  const double elevation = radians(def.elevation.value_or(view.flat ? 0.0 : kDefaultElevation));
  view.centre = (box.min + box.max) * 0.5;
  view.towardsEye = directionOf(azimuth, elevation);
  const glm::dvec3 worldUp = std::abs(view.towardsEye.y) > 0.999 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
  view.right = glm::normalize(glm::cross(worldUp, view.towardsEye));
  view.up = glm::cross(view.towardsEye, view.right);
  view.keyLight = directionOf(azimuth + radians(kKeyAzimuth), radians(kKeyElevation));
  view.perspective = def.fieldOfView > 0;

  std::array<glm::dvec3, 8> corners;  // in the camera's axes, from the centre
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                       (corner & 4) ? box.max.z : box.min.z);
    const glm::dvec3 d = p - view.centre;
    corners[corner] = {glm::dot(d, view.right), glm::dot(d, view.up), glm::dot(d, view.towardsEye)};
  }
  const double usableX = def.width * (0.5 - def.margin);
  const double usableY = def.height * (0.5 - def.margin);
  if (!view.perspective) {
    double halfX = 0, halfY = 0;
    for (const glm::dvec3& c : corners) halfX = std::max(halfX, std::abs(c.x)), halfY = std::max(halfY, std::abs(c.y));
    view.focal = std::min(halfX > 0 ? usableX / halfX : std::numeric_limits<double>::infinity(),
                          halfY > 0 ? usableY / halfY : std::numeric_limits<double>::infinity());
    if (!std::isfinite(view.focal)) view.focal = 1;
    view.distance = std::max(extent, 1e-300);
    return view;
  }
  // The nearest distance at which every corner fits, then the box centred and enlarged to
  // fill the picture as far as its margin allows.
  view.focal = std::min(def.width, def.height) * 0.5 / std::tan(radians(def.fieldOfView) / 2);
  double distance = 0, nearest = -std::numeric_limits<double>::infinity();
  for (const glm::dvec3& c : corners) {
    distance = std::max(distance, c.z + std::max(std::abs(c.x) * view.focal / usableX, std::abs(c.y) * view.focal / usableY));
    nearest = std::max(nearest, c.z);
  }
  if (!(distance > nearest)) distance = nearest + std::max(extent, 1.0);
  view.distance = distance;
  double minX = std::numeric_limits<double>::infinity(), maxX = -minX, minY = minX, maxY = -minX;
  for (const glm::dvec3& c : corners) {
    const double w = distance - c.z;
    minX = std::min(minX, c.x / w), maxX = std::max(maxX, c.x / w);
    minY = std::min(minY, c.y / w), maxY = std::max(maxY, c.y / w);
  }
  const double spanX = maxX - minX, spanY = maxY - minY;
  double zoom = std::min(spanX > 0 ? 2 * usableX / (view.focal * spanX) : std::numeric_limits<double>::infinity(),
                         spanY > 0 ? 2 * usableY / (view.focal * spanY) : std::numeric_limits<double>::infinity());
  if (!std::isfinite(zoom)) zoom = 1;
  view.focal *= zoom;
  view.cx = def.width * 0.5 - view.focal * (minX + maxX) / 2;
  view.cy = def.height * 0.5 + view.focal * (minY + maxY) / 2;
  view.eye = view.centre + view.towardsEye * distance;
  return view;
}

Image renderGeometry(const Geometry& geometry, const RenderDef& def) {
  const CameraView view = cameraOf(geometry, def);
  const Look& look = def.look;
  const glm::dvec3 background = linear(Color{look.background[0] / 255.0, look.background[1] / 255.0,
                                             look.background[2] / 255.0});
  Image image{def.width, def.height, std::vector<uint8_t>(static_cast<std::size_t>(def.width) * def.height * 3)};
  const Box& box = def.framing && !def.framing->empty ? *def.framing : geometry.bounds();
  if (box.empty || geometry.empty()) {
    for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = look.background[i % 3];
    return image;
  }
  const Mesh& mesh = geometry.mesh();
  const std::vector<Segment>& segments = geometry.segments();
  if (mesh.triangles.size() >= kLine || segments.size() >= kLine)
    throw std::length_error("a picture takes at most 2^31 - 1 triangles and as many lines");

  CanvasCamera camera{view};
  camera.view.focal *= kSupersample;
  camera.view.cx *= kSupersample;
  camera.view.cy *= kSupersample;
  Canvas canvas{def.width * kSupersample, def.height * kSupersample, {}, {}};
  const std::size_t samples = static_cast<std::size_t>(canvas.width) * canvas.height;
  canvas.nearness.assign(samples, -std::numeric_limits<double>::infinity());
  canvas.seen.assign(samples, kNothing);

  // Pass 1: what each sample sees.
  std::vector<Projected> projected(mesh.positions.size());
  // Perspective: nothing at or behind the eye is drawn (the camera stands outside the
  // framed box, so only geometry outside it can be there).
  const double nearLimit = 1e-9 * camera.view.distance;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) projected[i] = camera.project(mesh.positions[i]);
  auto inFront = [&](const Projected& p) { return !view.perspective || p.inverseW * nearLimit < 1; };
  for (uint32_t index = 0; index < mesh.triangles.size(); ++index) {
    const Triangle& t = mesh.triangles[index];
    const Projected &a = projected[t.position[0]], &b = projected[t.position[1]], &c = projected[t.position[2]];
    if (!(a.inverseW > 0 && b.inverseW > 0 && c.inverseW > 0) || !inFront(a) || !inFront(b) || !inFront(c)) continue;
    rasterise(canvas.width, canvas.height, a, b, c, [&](int x, int y, const Weights& w) {
      canvas.plot(x, y, w.w0 * a.nearness + w.w1 * b.nearness + w.w2 * c.nearness, index);
    });
  }
  const double lineWidth = std::max(1.0, std::round(std::min(canvas.width, canvas.height) / 400.0));
  for (uint32_t index = 0; index < segments.size(); ++index) {
    const Projected a = camera.project(segments[index].start), b = camera.project(segments[index].end);
    if (!(a.inverseW > 0 && b.inverseW > 0) || !inFront(a) || !inFront(b)) continue;
    drawLine(canvas, a, b, lineWidth, kLine | index);
  }

  // The shadow map, when anything casts a shadow on something that shows it.
  const glm::dvec3 size = box.max - box.min;
  const double extent = std::max({size.x, size.y, size.z});
  const bool floorShown = look.floorShadow > 0 && !view.flat && view.towardsEye.y > kMinFloorSine;
  std::optional<ShadowMap> shadows;
  if (!mesh.triangles.empty() && look.key > 0) {
    const int side = std::clamp(std::max(def.width, def.height), kMinShadowMap, kMaxShadowMap);
    shadows.emplace(mesh, box, view.keyLight, look.softness * extent, side);
  }

  // Pass 2: each sample shaded once, the samples of a pixel averaged in linear light.
  const std::array<glm::dvec3, kPaletteSize> albedo = lookPalette(look, 1);
  const std::array<glm::dvec3, kPaletteSize> lineColour = lookPalette(look, look.lineShade);
  const glm::dvec3 key = view.keyLight;
  const double floorY = box.min.y;
  auto empty = [&](double sx, double sy) -> glm::dvec3 {
    if (!floorShown || !shadows) return background;
    const auto [origin, direction] = camera.ray(sx, sy);
    if (!(direction.y < 0)) return background;
    const double along = (floorY - origin.y) / direction.y;
    if (!(along > 0)) return background;
    const double lit = shadows->floorLit(origin + direction * along);
    return background * (1 - look.floorShadow * (1 - lit));
  };
  auto shade = [&](std::size_t i, double sx, double sy) -> glm::dvec3 {
    const uint32_t what = canvas.seen[i];
    if (what == kNothing) return empty(sx, sy);
    if (what & kLine) return lineColour[segments[what & ~kLine].material % kPaletteSize];
    const Triangle& t = mesh.triangles[what];
    const Projected &a = projected[t.position[0]], &b = projected[t.position[1]], &c = projected[t.position[2]];
    const Weights w = weightsAt(a, b, c, sx, sy);
    // Perspective-correct weights: the screen's weights over each corner's distance.
    double q0 = w.w0 * a.inverseW, q1 = w.w1 * b.inverseW, q2 = w.w2 * c.inverseW;
    const double sum = q0 + q1 + q2;
    q0 /= sum, q1 /= sum, q2 /= sum;
    const glm::dvec3 p = mesh.positions[t.position[0]] * q0 + mesh.positions[t.position[1]] * q1 +
                         mesh.positions[t.position[2]] * q2;
    glm::dvec3 n = mesh.normals[t.normal[0]] * q0 + mesh.normals[t.normal[1]] * q1 + mesh.normals[t.normal[2]] * q2;
    glm::dvec3 g = glm::cross(mesh.positions[t.position[1]] - mesh.positions[t.position[0]],
                              mesh.positions[t.position[2]] - mesh.positions[t.position[0]]);
    const double nLength = glm::length(n), gLength = glm::length(g);
    g = gLength > 0 ? g / gLength : view.towardsEye;
    n = nLength > 0 ? n / nLength : g;
    const glm::dvec3 toEye = view.perspective ? glm::normalize(view.eye - p) : view.towardsEye;
    // Two-sided: a triangle seen from its back (a disc, a leaf) is lit as its other side.
    if (glm::dot(g, toEye) < 0) n = -n, g = -g;
    const double diffuse = glm::dot(n, key);
    double lit = 0;
    if (diffuse > 0 && glm::dot(g, key) > 0) lit = shadows ? shadows->lit(p, g) : 1;
    const glm::dvec3 halfway = glm::normalize(key + toEye);
    const double highlight =
        diffuse > 0 && look.specular > 0 ? look.specular * std::pow(std::max(0.0, glm::dot(n, halfway)), look.shininess) : 0;
    const double light = look.ambient + look.fill * std::max(0.0, glm::dot(n, toEye)) + look.key * std::max(0.0, diffuse) * lit;
    return albedo[t.material % kPaletteSize] * light + glm::dvec3(highlight * lit);
  };
  const Encoder encode;
  for (int y = 0; y < def.height; ++y) {
    for (int x = 0; x < def.width; ++x) {
      glm::dvec3 sum(0.0);
      // A pixel that sees nothing but the floor: its shadow is soft, one sample at the
      // pixel's centre is enough (most of a picture is such pixels).
      bool nothing = true;
      for (int sy = 0; sy < kSupersample; ++sy)
        for (int sx = 0; sx < kSupersample; ++sx)
          nothing = nothing && canvas.seen[static_cast<std::size_t>(y * kSupersample + sy) * canvas.width +
                                           x * kSupersample + sx] == kNothing;
      if (nothing) {
        sum = empty((x + 0.5) * kSupersample, (y + 0.5) * kSupersample);
      } else {
        for (int sy = 0; sy < kSupersample; ++sy) {
          for (int sx = 0; sx < kSupersample; ++sx) {
            const int cx = x * kSupersample + sx, cy = y * kSupersample + sy;
            sum += shade(static_cast<std::size_t>(cy) * canvas.width + cx, cx + 0.5, cy + 0.5);
          }
        }
        sum /= kSupersample * kSupersample;
      }
      uint8_t* out = &image.rgb[(static_cast<std::size_t>(y) * def.width + x) * 3];
      out[0] = encode(sum.x), out[1] = encode(sum.y), out[2] = encode(sum.z);
    }
  }
  return image;
}

}  // namespace ontogen
