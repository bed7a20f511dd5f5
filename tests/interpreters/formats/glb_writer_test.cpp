// The animated glTF binary read back: its materials carry the palette in linear light.

#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "interpreters/formats/glb_writer.h"
#include "interpreters/geometry.h"
#include "interpreters/palette.h"

namespace ontogen {
namespace {

// The JSON chunk of a .glb (the header is 12 bytes, then the chunk's length and type).
nlohmann::json jsonChunkOf(const std::string& glb) {
  uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, length));
}

TEST(GlbWriter, MaterialsAreThePaletteInLinearLight) {
  Geometry geometry;
  geometry.setMaterial(0);
  geometry.addCylinder({0, 0, 0}, {0, 1, 0}, 0.1, true);
  geometry.setMaterial(2);
  geometry.addSphere({0, 2, 0}, 0.5);
  GlbAnimationWriter writer;
  writer.addFrame(geometry, 0);
  std::ostringstream out;
  writer.write(out);
  const nlohmann::json gltf = jsonChunkOf(out.str());
  ASSERT_EQ(gltf["materials"].size(), 2u);
  // Palette 0 is sRGB (0.62, 0.55, 0.45) and 2 is (0.85, 0.20, 0.20); in linear light,
  // by IEC 61966-2-1's curve ((c + 0.055) / 1.055)^2.4, they are these.
  const auto& stem = gltf["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"];
  EXPECT_NEAR(stem[0].get<double>(), 0.342392, 1e-6);
  EXPECT_NEAR(stem[1].get<double>(), 0.263273, 1e-6);
  EXPECT_NEAR(stem[2].get<double>(), 0.170645, 1e-6);
  EXPECT_EQ(stem[3].get<double>(), 1.0);
  const auto& red = gltf["materials"][1]["pbrMetallicRoughness"]["baseColorFactor"];
  EXPECT_NEAR(red[0].get<double>(), 0.692071, 1e-6);
  EXPECT_NEAR(red[1].get<double>(), 0.033105, 1e-6);
  EXPECT_EQ(gltf["materials"][1]["name"], "ontogen_2");
}

TEST(Palette, LinearFromSrgbFollowsBothPiecesOfTheCurve) {
  EXPECT_DOUBLE_EQ(linearFromSrgb(0.0), 0.0);
  EXPECT_DOUBLE_EQ(linearFromSrgb(1.0), 1.0);
  EXPECT_NEAR(linearFromSrgb(0.03), 0.03 / 12.92, 1e-15);  // the straight piece near black
  EXPECT_NEAR(linearFromSrgb(0.5), 0.214041, 1e-6);
  EXPECT_DOUBLE_EQ(linearFromSrgb(-1.0), 0.0);  // clamped
}

}  // namespace
}  // namespace ontogen
