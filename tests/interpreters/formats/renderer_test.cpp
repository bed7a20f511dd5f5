// The software renderer checked by value: the light on a sphere against Lambert's law in
// linear light, perspective against the ratio of distances, the key light's shadow on a
// plate and on the floor, smooth normals against flat ones, the looks, and the same bytes
// on every run.
#include "interpreters/formats/renderer.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "interpreters/formats/look.h"
#include "interpreters/palette.h"
#include "lang/directives.h"

namespace ontogen {
namespace {

// The sRGB encoding of a linear value, as a picture's 8 bits hold it.
double encoded(double linearValue) {
  const double v = std::clamp(linearValue, 0.0, 1.0);
  return 255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055);
}

const uint8_t* pixel(const Image& image, int x, int y) {
  return &image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3];
}

// A look with no highlight, no floor and no palette change: a lit colour is exactly
// albedo x (ambient + fill n.v + key n.l shadow).
Look plainLook() {
  Look look;
  look.ambient = 0.1;
  look.fill = 0.2;
  look.key = 0.7;
  look.specular = 0;
  look.floorShadow = 0;
  return look;
}

// Red, palette colour 0's linear value: the channel the tests read.
double albedoRed(uint32_t material) { return linearFromSrgb(paletteColor(material).r); }

// A sphere seen from +x (its poles lie along z, so the view meets its equator), finely
// tessellated: at the picture's centre the normal points at the eye; where the normal
// points at the key light the key light counts fully. Both pixels are what the formula
// gives, to two levels of 255.
TEST(Renderer, ASphereIsLitByLambertsLawInLinearLight) {
  Geometry sphere(MeshDef{.sphereSlices = 96, .sphereStacks = 48});
  sphere.addSphere({0, 0, 0}, 1);
  RenderDef def;
  def.width = def.height = 101;
  def.azimuth = 90;
  def.elevation = 0;
  def.look = plainLook();
  const Image image = renderGeometry(sphere, def);
  const CameraView view = cameraOf(sphere, def);
  const glm::dvec3 l = view.keyLight;
  const double albedo = albedoRed(0);
  const Look& look = def.look;

  // The centre: n = v = towards the eye.
  const glm::dvec3 front(1, 0, 0);
  ASSERT_NEAR(glm::dot(view.towardsEye, front), 1, 1e-12);
  const double centre = encoded(albedo * (look.ambient + look.fill + look.key * glm::dot(front, l)));
  EXPECT_NEAR(pixel(image, 50, 50)[0], centre, 2);

  // Where n = l (on the side facing the light, seen from the eye).
  const glm::dvec3 facing = l;  // the point of the unit sphere whose normal is l
  const glm::dvec3 at = view.project(facing);
  const glm::dvec3 toEye = glm::normalize(view.eye - facing);
  ASSERT_GT(glm::dot(facing, toEye), 0.2);  // seen
  const double lit = encoded(albedo * (look.ambient + look.fill * glm::dot(facing, toEye) + look.key));
  EXPECT_NEAR(pixel(image, static_cast<int>(at.x), static_cast<int>(at.y))[0], lit, 2);
  // Brighter on the light's side by the key light's share the centre does not get.
  EXPECT_GT(lit - centre, 10);

  // The side away from the light, seen from the eye: ambient and fill only.
  const glm::dvec3 away = glm::normalize(glm::dvec3(1, 0, 0) - glm::dvec3(0, l.y, l.z) * 1.2);
  if (glm::dot(away, l) < 0) {
    const glm::dvec3 p = view.project(away);
    const double dark = encoded(albedo * (look.ambient + look.fill * glm::dot(away, glm::normalize(view.eye - away))));
    EXPECT_NEAR(pixel(image, static_cast<int>(p.x), static_cast<int>(p.y))[0], dark, 2);
  }
}

// Smooth normals: across a sphere of few facets the light changes little from pixel to
// pixel, where flat facets would step. The same sphere with every corner given its
// facet's normal steps.
TEST(Renderer, TheMeshsNormalsMakeRoundSurfacesSmooth) {
  Geometry smooth(MeshDef{.sphereSlices = 8, .sphereStacks = 4});
  smooth.addSphere({0, 0, 0}, 1);
  Mesh facets;
  const Mesh& mesh = smooth.mesh();
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.position[0]], b = mesh.positions[t.position[1]], c = mesh.positions[t.position[2]];
    const uint32_t first = static_cast<uint32_t>(facets.positions.size());
    facets.positions.insert(facets.positions.end(), {a, b, c});
    facets.normals.push_back(glm::normalize(glm::cross(b - a, c - a)));
    const uint32_t normal = static_cast<uint32_t>(facets.normals.size() - 1);
    facets.triangles.push_back(Triangle{{first, first + 1, first + 2}, {normal, normal, normal}, {0, 0, 0}, 0});
  }
  facets.texcoords.push_back({0, 0});
  Geometry flat;
  flat.addMesh(facets);
  RenderDef def;
  def.width = def.height = 81;
  def.azimuth = 90;
  def.elevation = 0;
  def.look = plainLook();
  auto largestStep = [&](const Geometry& geometry) {
    const Image image = renderGeometry(geometry, def);
    int largest = 0;
    // Along the middle row, inside the sphere.
    for (int x = 25; x < 56; ++x) largest = std::max(largest, std::abs(pixel(image, x + 1, 40)[0] - pixel(image, x, 40)[0]));
    return largest;
  };
  const int smoothStep = largestStep(smooth), flatStep = largestStep(flat);
  EXPECT_LE(smoothStep, 6);
  EXPECT_GE(flatStep, 3 * smoothStep);
}

// Two equal squares facing the camera, one twice as far along the view as the other
// (measured from the eye): in perspective the near one is larger by the ratio of their
// distances; orthographic, they are the same size.
TEST(Renderer, PerspectiveShrinksByTheRatioOfDistances) {
  auto square = [](Geometry& g, glm::dvec3 centre) {
    Mesh m;
    const double h = 1;
    m.positions = {centre + glm::dvec3(-h, -h, 0), centre + glm::dvec3(h, -h, 0), centre + glm::dvec3(h, h, 0),
                   centre + glm::dvec3(-h, h, 0)};
    m.normals = {{0, 0, 1}};
    m.texcoords = {{0, 0}};
    m.triangles = {Triangle{{0, 1, 2}, {0, 0, 0}, {0, 0, 0}, 0}, Triangle{{0, 2, 3}, {0, 0, 0}, {0, 0, 0}, 0}};
    g.addMesh(m);
  };
  Geometry geometry;
  square(geometry, {-2.5, 0, 0});
  square(geometry, {2.5, 0, -12});
  RenderDef def;
  def.width = 400;
  def.height = 200;
  def.azimuth = 0;
  def.elevation = 0;
  def.look = plainLook();
  // The width in pixels of what is not background along the row through y.
  auto widths = [&](const Image& image, const CameraView& view) {
    std::vector<int> runs;
    const int y = static_cast<int>(view.project({0, 0, 0}).y);
    int run = 0;
    for (int x = 0; x < image.width; ++x) {
      const bool drawn = std::abs(pixel(image, x, y)[0] - kBackground[0]) > 40;
      if (drawn) ++run;
      if ((!drawn || x + 1 == image.width) && run > 0) runs.push_back(run), run = 0;
    }
    return runs;
  };
  const CameraView view = cameraOf(geometry, def);
  ASSERT_TRUE(view.perspective);
  const std::vector<int> seen = widths(renderGeometry(geometry, def), view);
  ASSERT_EQ(seen.size(), 2u);
  const double nearDistance = glm::dot(view.eye - glm::dvec3(-2.5, 0, 0), view.towardsEye);
  const double farDistance = glm::dot(view.eye - glm::dvec3(2.5, 0, -12), view.towardsEye);
  // Each width is exact to a pixel at either end.
  EXPECT_NEAR(static_cast<double>(seen[0]) / seen[1], farDistance / nearDistance, 2.0 / seen[1] * farDistance / nearDistance);
  EXPECT_GT(static_cast<double>(seen[0]) / seen[1], 1.3);
  // The camera's own projection says the same as the picture.
  EXPECT_NEAR(view.project({-1.5, 0, 0}).x - view.project({-3.5, 0, 0}).x, seen[0], 1.5);

  def.fieldOfView = 0;
  const CameraView orthographic = cameraOf(geometry, def);
  EXPECT_FALSE(orthographic.perspective);
  const std::vector<int> flat = widths(renderGeometry(geometry, def), orthographic);
  ASSERT_EQ(flat.size(), 2u);
  EXPECT_NEAR(flat[0], flat[1], 1);
}

// A ball above a plate, and the key light: the plate's pixel where the ball's shadow
// centre falls lacks exactly the key light's share; a pixel of the plate out of the
// shadow has it.
TEST(Renderer, TheKeyLightsShadowDarkensAKnownPixel) {
  Geometry geometry;
  geometry.setMaterial(2);
  geometry.addDisc({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0, 4);  // faces (0, 0, 1) x (1, 0, 0) = +y
  geometry.setMaterial(0);
  geometry.addSphere({0, 1.5, 0}, 0.5);
  RenderDef def;
  def.width = def.height = 161;
  def.look = plainLook();
  const CameraView view = cameraOf(geometry, def);
  const glm::dvec3 l = view.keyLight;
  const glm::dvec3 shadowCentre = glm::dvec3(0, 1.5, 0) - l * (1.5 / l.y);
  ASSERT_LT(glm::length(shadowCentre), 3.5);  // on the plate
  const glm::dvec3 up(0, 1, 0);
  auto expected = [&](const glm::dvec3& p, double lit) {
    const glm::dvec3 toEye = glm::normalize(view.eye - p);
    const Look& look = def.look;
    return encoded(albedoRed(2) * (look.ambient + look.fill * glm::dot(up, toEye) + look.key * glm::dot(up, l) * lit));
  };
  const Image image = renderGeometry(geometry, def);
  const glm::dvec3 at = view.project(shadowCentre);
  EXPECT_NEAR(pixel(image, static_cast<int>(at.x), static_cast<int>(at.y))[0], expected(shadowCentre, 0), 2);
  // Across the ball from its shadow, the plate is in the light.
  const glm::dvec3 sunny = glm::dvec3(-shadowCentre.x, 0, -shadowCentre.z) * 1.2;
  const glm::dvec3 sunnyAt = view.project(sunny);
  EXPECT_NEAR(pixel(image, static_cast<int>(sunnyAt.x), static_cast<int>(sunnyAt.y))[0], expected(sunny, 1), 2);
  EXPECT_GT(expected(sunny, 1) - expected(shadowCentre, 0), 20);
}

// The floor: with nothing under a floating ball but the floor (the plane through the
// framed box's lowest point), the background where the ball's shadow falls is darkened
// by the look's floorShadow in linear light; elsewhere it is the background.
TEST(Renderer, TheFloorTakesTheShadow) {
  Geometry geometry;
  geometry.addSphere({0, 1.5, 0}, 0.5);
  geometry.addSphere({3, 0, 3}, 0.01);  // sets the floor at y = -0.01, far from the shadow
  RenderDef def;
  def.width = def.height = 161;
  const Look& look = def.look;  // light: floorShadow 0.35
  const CameraView view = cameraOf(geometry, def);
  const glm::dvec3 l = view.keyLight;
  const double floorY = -0.01;
  const glm::dvec3 shadowCentre = glm::dvec3(0, 1.5, 0) - l * ((1.5 - floorY) / l.y);
  const Image image = renderGeometry(geometry, def);
  const glm::dvec3 at = view.project(shadowCentre);
  const uint8_t* shadowed = pixel(image, static_cast<int>(at.x), static_cast<int>(at.y));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(shadowed[k], encoded(linearFromSrgb(kBackground[k] / 255.0) * (1 - look.floorShadow)), 1.5) << k;
  EXPECT_EQ(pixel(image, 2, 2)[0], kBackground[0]);
  // The paper look has no floor.
  def.look = *findLook("paper");
  const Image paper = renderGeometry(geometry, def);
  EXPECT_EQ(pixel(paper, static_cast<int>(at.x), static_cast<int>(at.y))[0], def.look.background[0]);
}

TEST(Renderer, LooksAreNamedAndMatchTheDirective) {
  std::vector<std::string_view> names = lookNames();
  EXPECT_EQ(lookList(), "light, dark, paper");
  const Directive* directive = findDirective("look");
  ASSERT_NE(directive, nullptr);
  EXPECT_EQ(std::vector<std::string_view>(directive->words.begin(), directive->words.end()), names);
  EXPECT_FALSE(findLook("neon"));
  // Each look's empty picture is its background.
  Geometry sphere;
  sphere.addSphere({0, 0, 0}, 1);
  for (std::string_view name : names) {
    RenderDef def;
    def.width = def.height = 24;
    def.look = *findLook(name);
    const Image image = renderGeometry(sphere, def);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(pixel(image, 0, 0)[k], def.look.background[k]) << name;
    EXPECT_NE(pixel(image, 12, 12)[0], def.look.background[0]) << name;
  }
}

// One thread, a fixed order: the same bytes each time.
TEST(Renderer, TheSameGeometryGivesTheSameBytes) {
  Geometry geometry;
  geometry.addCylinder({0, 0, 0}, {0, 2, 0}, 0.3, true);
  geometry.addSphere({0, 2.3, 0}, 0.4);
  geometry.addSegment({0, 0, 0}, {1, 1, 1});
  RenderDef def;
  def.width = 64;
  def.height = 48;
  const Image first = renderGeometry(geometry, def);
  EXPECT_EQ(renderGeometry(geometry, def).rgb, first.rgb);
  def.fieldOfView = 121;
  EXPECT_THROW(renderGeometry(geometry, def), std::invalid_argument);
}

}  // namespace
}  // namespace ontogen
