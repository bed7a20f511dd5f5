#include "interpreters/formats/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "interpreters/palette.h"

namespace ontogen {

namespace {

constexpr int kMaxSize = 8192;  // 200 MB of supersampled buffers at most
constexpr int kSupersample = 2;
constexpr double kAmbient = 0.3;  // shadowed sides stay readable
// A model thinner than this fraction of its size along z is flat (drawn in x-y).
constexpr double kFlatRatio = 1e-9;
constexpr double kDefaultAzimuth = 30;
constexpr double kDefaultElevation = 20;

struct Camera {
  glm::dvec3 centre, right, up, towardsEye;
  double scale = 1;  // pixels per model unit
  double cx = 0, cy = 0;
};

struct Canvas {
  int width, height;
  std::vector<double> depth;  // larger is nearer
  std::vector<float> rgb;

  void plot(int x, int y, double z, const glm::dvec3& colour) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::size_t i = static_cast<std::size_t>(y) * width + x;
    if (z < depth[i]) return;
    depth[i] = z;
    rgb[3 * i] = static_cast<float>(colour.r);
    rgb[3 * i + 1] = static_cast<float>(colour.g);
    rgb[3 * i + 2] = static_cast<float>(colour.b);
  }
};

glm::dvec3 toScreen(const Camera& c, const glm::dvec3& p) {
  glm::dvec3 d = p - c.centre;
  return {c.cx + glm::dot(d, c.right) * c.scale, c.cy - glm::dot(d, c.up) * c.scale, glm::dot(d, c.towardsEye)};
}

void fillTriangle(Canvas& canvas, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, const glm::dvec3& colour) {
  double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (std::abs(area) < 1e-12) return;
  int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
  int x1 = std::min(canvas.width - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
  int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
  int y1 = std::min(canvas.height - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
  for (int y = y0; y <= y1; ++y) {
    double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      double px = x + 0.5;
      double w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
      double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
      double w2 = 1 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      canvas.plot(x, y, w0 * a.z + w1 * b.z + w2 * c.z, colour);
    }
  }
}

void drawLine(Canvas& canvas, const glm::dvec3& a, const glm::dvec3& b, double width, const glm::dvec3& colour) {
  double length = std::hypot(b.x - a.x, b.y - a.y);
  int steps = std::max(1, static_cast<int>(std::ceil(length * 2)));
  int half = std::max(0, static_cast<int>(std::floor(width / 2)));
  for (int i = 0; i <= steps; ++i) {
    double t = static_cast<double>(i) / steps;
    glm::dvec3 p = a + (b - a) * t;
    int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    for (int dy = -half; dy <= half; ++dy) {
      for (int dx = -half; dx <= half; ++dx) canvas.plot(x + dx, y + dy, p.z + 1e-9, colour);
    }
  }
}

glm::dvec3 rgbOf(uint32_t material) {
  Color c = paletteColor(material);
  return {c.r, c.g, c.b};
}

}  // namespace

void checkRenderDef(const RenderDef& def) {
  if (def.width < 1 || def.width > kMaxSize || def.height < 1 || def.height > kMaxSize) {
    throw std::invalid_argument("picture size must be in 1..8192 pixels, got " + std::to_string(def.width) + "x" +
                                std::to_string(def.height));
  }
  if (def.elevation && (*def.elevation < -90 || *def.elevation > 90)) {
    throw std::invalid_argument("elevation must be in -90..90 degrees");
  }
  if (!(def.margin >= 0 && def.margin < 0.5)) throw std::invalid_argument("margin must be in [0, 0.5)");
}

uint64_t renderBytes(const RenderDef& def) {
  const uint64_t pixels = static_cast<uint64_t>(std::max(def.width, 0)) * static_cast<uint64_t>(std::max(def.height, 0));
  // The supersampled canvas: a depth (double) and a colour (3 floats) a sample.
  const uint64_t canvas = pixels * kSupersample * kSupersample * (sizeof(double) + 3 * sizeof(float));
  return canvas + pixels * 6;  // the picture, and about as much for its PNG
}

Image renderGeometry(const Geometry& geometry, const RenderDef& def) {
  checkRenderDef(def);
  Canvas canvas{def.width * kSupersample, def.height * kSupersample, {}, {}};
  const std::size_t pixels = static_cast<std::size_t>(canvas.width) * canvas.height;
  canvas.depth.assign(pixels, -std::numeric_limits<double>::infinity());
  canvas.rgb.resize(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i) {
    for (int k = 0; k < 3; ++k) canvas.rgb[3 * i + k] = kBackground[k] / 255.0f;
  }

  const Box& box = def.framing && !def.framing->empty ? *def.framing : geometry.bounds();
  if (!box.empty && !geometry.empty()) {
    const glm::dvec3 size = box.max - box.min;
    const double extent = std::max({size.x, size.y, size.z});
    const bool flat = size.z <= kFlatRatio * std::max(extent, 1e-300);
    const double azimuth = def.azimuth.value_or(flat ? 0.0 : kDefaultAzimuth) * std::numbers::pi / 180;
    const double elevation = def.elevation.value_or(flat ? 0.0 : kDefaultElevation) * std::numbers::pi / 180;
    Camera camera;
    camera.centre = (box.min + box.max) * 0.5;
    camera.towardsEye = {std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                         std::cos(azimuth) * std::cos(elevation)};
    glm::dvec3 worldUp = std::abs(camera.towardsEye.y) > 0.999 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
    camera.right = glm::normalize(glm::cross(worldUp, camera.towardsEye));
    camera.up = glm::cross(camera.towardsEye, camera.right);
    // Fit the projected corners of the box.
    double halfX = 0, halfY = 0;
    for (int corner = 0; corner < 8; ++corner) {
      glm::dvec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                   (corner & 4) ? box.max.z : box.min.z);
      glm::dvec3 d = p - camera.centre;
      halfX = std::max(halfX, std::abs(glm::dot(d, camera.right)));
      halfY = std::max(halfY, std::abs(glm::dot(d, camera.up)));
    }
    const double usableX = canvas.width * (0.5 - def.margin);
    const double usableY = canvas.height * (0.5 - def.margin);
    camera.scale = std::min(halfX > 0 ? usableX / halfX : std::numeric_limits<double>::infinity(),
                            halfY > 0 ? usableY / halfY : std::numeric_limits<double>::infinity());
    if (!std::isfinite(camera.scale)) camera.scale = 1;
    camera.cx = canvas.width * 0.5;
    camera.cy = canvas.height * 0.5;
    // The light comes from above-left of the viewer.
    const glm::dvec3 light = glm::normalize(camera.towardsEye * 0.8 + camera.up * 0.5 - camera.right * 0.35);

    const Mesh& mesh = geometry.mesh();
    for (const Triangle& t : mesh.triangles) {
      const glm::dvec3& p0 = mesh.positions[t.position[0]];
      const glm::dvec3& p1 = mesh.positions[t.position[1]];
      const glm::dvec3& p2 = mesh.positions[t.position[2]];
      glm::dvec3 normal = glm::cross(p1 - p0, p2 - p0);
      double length = glm::length(normal);
      if (!(length > 0)) continue;
      double lambert = std::abs(glm::dot(normal / length, light));
      glm::dvec3 colour = rgbOf(t.material) * (kAmbient + (1 - kAmbient) * lambert);
      fillTriangle(canvas, toScreen(camera, p0), toScreen(camera, p1), toScreen(camera, p2), colour);
    }
    const double lineWidth = std::max(1.0, std::round(std::min(canvas.width, canvas.height) / 400.0));
    for (const Segment& s : geometry.segments()) {
      drawLine(canvas, toScreen(camera, s.start), toScreen(camera, s.end), lineWidth, rgbOf(s.material) * 0.6);
    }
  }

  Image image{def.width, def.height, std::vector<uint8_t>(static_cast<std::size_t>(def.width) * def.height * 3)};
  for (int y = 0; y < def.height; ++y) {
    for (int x = 0; x < def.width; ++x) {
      for (int k = 0; k < 3; ++k) {
        double sum = 0;
        for (int sy = 0; sy < kSupersample; ++sy) {
          for (int sx = 0; sx < kSupersample; ++sx) {
            std::size_t i = static_cast<std::size_t>(y * kSupersample + sy) * canvas.width + x * kSupersample + sx;
            sum += canvas.rgb[3 * i + k];
          }
        }
        double value = sum / (kSupersample * kSupersample);
        image.rgb[(static_cast<std::size_t>(y) * def.width + x) * 3 + k] =
            static_cast<uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255));
      }
    }
  }
  return image;
}

}  // namespace ontogen
