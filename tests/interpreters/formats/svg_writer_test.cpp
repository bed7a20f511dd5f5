#include "interpreters/formats/svg_writer.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "interpreters/geometry.h"
#include "interpreters/geometry/turtle.h"

namespace ontogen {
namespace {

struct Instruction {
  std::string command;
  std::vector<double> args;
};

Geometry draw(const std::vector<Instruction>& word, const TurtleDef& def = {}) {
  Turtle turtle(def);
  Geometry geometry;
  for (const Instruction& i : word) turtle.execute(i.command, i.args, geometry);
  return geometry;
}

std::string svgOf(const Geometry& geometry, const SvgOptions& options = {}) {
  std::ostringstream out;
  writeSvg(geometry, out, options);
  return out.str();
}

/// A tiny XML check: every start tag is closed in order, one root element, comments and
/// the declaration skipped, attribute values quoted. Returns "" or what is wrong.
std::string checkWellFormed(const std::string& text) {
  std::vector<std::string> open;
  int roots = 0;
  std::size_t i = 0;
  while ((i = text.find('<', i)) != std::string::npos) {
    if (text.compare(i, 4, "<!--") == 0) {
      std::size_t end = text.find("-->", i);
      if (end == std::string::npos) return "unclosed comment";
      if (text.substr(i + 4, end - i - 4).find("--") != std::string::npos) return "-- in comment";
      i = end + 3;
      continue;
    }
    std::size_t end = text.find('>', i);
    if (end == std::string::npos) return "unclosed tag";
    std::string tag = text.substr(i + 1, end - i - 1);
    i = end + 1;
    if (tag.starts_with('?')) {
      if (!tag.ends_with('?')) return "bad declaration";
      continue;
    }
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return "unbalanced quotes in <" + tag;
    if (tag.starts_with('/')) {
      if (open.empty() || open.back() != tag.substr(1)) return "mismatched </" + tag.substr(1);
      open.pop_back();
      continue;
    }
    std::string name = tag.substr(0, tag.find_first_of(" /"));
    if (open.empty()) ++roots;
    if (!tag.ends_with('/')) open.push_back(name);
  }
  if (!open.empty()) return "unclosed <" + open.back();
  if (roots != 1) return "expected one root element";
  return "";
}

int countOf(const std::string& text, const std::string& needle) {
  int count = 0;
  for (std::size_t i = text.find(needle); i != std::string::npos; i = text.find(needle, i + 1)) {
    ++count;
  }
  return count;
}

/// The value of the first attribute called name.
std::string attribute(const std::string& text, const std::string& name) {
  const std::string key = " " + name + "=\"";
  std::size_t begin = text.find(key);
  if (begin == std::string::npos) return "";
  begin += key.size();
  return text.substr(begin, text.find('"', begin) - begin);
}

std::string withoutComments(std::string text) {
  for (std::size_t i; (i = text.find("<!--")) != std::string::npos;) {
    text.erase(i, text.find("-->", i) + 3 - i);
  }
  return text;
}

TEST(SvgWriterTest, IsWellFormedWithOneElementPerPrimitive) {
  Geometry geometry = draw({{"F", {}}, {"+", {}}, {"F", {}}, {"[", {}}, {"-", {30}}, {"F", {}},
                            {"]", {}}, {"!", {0.2}}, {"F", {}}, {"cC", {1, 1}},
                            {"disc", {0.5, 1}}, {"disc", {0.3}}, {"sphere", {0.4}}});
  ASSERT_EQ(geometry.segmentCount(), 3u);
  ASSERT_EQ(geometry.cylinders().size(), 2u);
  std::string svg = svgOf(geometry);
  EXPECT_EQ(checkWellFormed(svg), "") << svg;
  EXPECT_TRUE(svg.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg "));
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(svg.find("<rect x=\"0\" y=\"0\""), std::string::npos);
  EXPECT_NE(svg.find("fill=\"white\""), std::string::npos);
  EXPECT_EQ(countOf(svg, "<line "), 5);  // 3 segments + 2 cylinders
  EXPECT_EQ(countOf(svg, "<path "), 2);  // 2 discs
  EXPECT_EQ(countOf(svg, "<circle "), 1);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  EXPECT_EQ(svg.find("\"-0\""), std::string::npos);
}

TEST(SvgWriterTest, LineCountEqualsSegmentCountForALargeCurve) {
  std::vector<Instruction> word;
  for (int i = 0; i < 500; ++i) {
    word.push_back({"F", {}});
    word.push_back({i % 3 == 0 ? "-" : "+", {60}});
  }
  Geometry geometry = draw(word);
  std::string svg = svgOf(geometry);
  EXPECT_EQ(checkWellFormed(svg), "");
  EXPECT_EQ(countOf(svg, "<line "), static_cast<int>(geometry.segmentCount()));
}

TEST(SvgWriterTest, ProjectsOntoXyWithYUpAndFitsTheViewBox) {
  // The square F+F+F+F spans x in [-1, 0], y in [0, 1]: scale (1000 - 2 * 20) / 1 = 960.
  std::string svg = svgOf(draw({{"F", {}}, {"+", {}}, {"F", {}}, {"+", {}}, {"F", {}},
                                {"+", {}}, {"F", {}}}));
  EXPECT_EQ(attribute(svg, "viewBox"), "0 0 1000 1000");
  EXPECT_EQ(attribute(svg, "width"), "1000");
  EXPECT_EQ(attribute(svg, "height"), "1000");
  // The first segment goes from the origin (bottom right) straight up.
  EXPECT_NE(svg.find("<line x1=\"980\" y1=\"980\" x2=\"980\" y2=\"20\"/>"), std::string::npos)
      << svg;
  EXPECT_NE(svg.find("<line x1=\"980\" y1=\"20\" x2=\"20\" y2=\"20\"/>"), std::string::npos);
}

TEST(SvgWriterTest, FlatDrawingGetsAFlatPicture) {
  std::string svg = svgOf(draw({{"-", {}}, {"F", {2}}}));
  EXPECT_EQ(attribute(svg, "viewBox"), "0 0 1000 40");
  EXPECT_NE(svg.find("<line x1=\"20\" y1=\"20\" x2=\"980\" y2=\"20\"/>"), std::string::npos);
}

TEST(SvgWriterTest, CylinderIsALineAsWideAsItsDiameter) {
  // !(3)F(10): x in [-3, 3], y in [-3, 13] (ends widened by the radius): scale 960 / 16.
  std::string svg = svgOf(draw({{"!", {3}}, {"F", {10}}}));
  EXPECT_EQ(countOf(svg, "<line "), 1);
  EXPECT_EQ(attribute(svg, "viewBox"), "0 0 400 1000");
  EXPECT_NE(svg.find("<line x1=\"200\" y1=\"800\" x2=\"200\" y2=\"200\" stroke=\"#666666\" "
                     "stroke-width=\"360\" stroke-linecap=\"butt\"/>"),
            std::string::npos)
      << svg;
}

TEST(SvgWriterTest, ThinCylindersAreWidenedToTheHairline) {
  SvgOptions options;
  options.hairline = 2;
  std::string svg = svgOf(draw({{"!", {1e-6}}, {"F", {10}}}), options);
  EXPECT_NE(svg.find("stroke-width=\"2\" stroke-linecap=\"butt\""), std::string::npos) << svg;
}

TEST(SvgWriterTest, IsDeterministicAndScaleFree) {
  auto word = [](double unit) {
    return draw({{"F", {unit}}, {"+", {33}}, {"F", {unit}}, {"&", {10}}, {"F", {unit}}});
  };
  std::string svg = svgOf(word(1));
  EXPECT_EQ(svg, svgOf(word(1)));
  // The same drawing at another scale differs only in the scale comment.
  std::string large = svgOf(word(1000));
  EXPECT_NE(svg, large);
  EXPECT_EQ(withoutComments(svg), withoutComments(large));
  // No exponents: fixed notation only.
  const std::string body = withoutComments(svg);
  for (std::size_t i = 1; i + 1 < body.size(); ++i) {
    if (body[i] == 'e' && std::isdigit(static_cast<unsigned char>(body[i - 1]))) {
      ADD_FAILURE() << "exponent at " << body.substr(i - 5, 10);
    }
  }
}

TEST(SvgWriterTest, FartherPrimitivesArePaintedFirst) {
  // A sphere at z = 1, then a line from z = 1 to 0, then a disc at z = 0: painted disc,
  // line, sphere (unsorted, spheres would come before lines).
  Geometry geometry = draw({{"^", {90}}, {"f", {1}}, {"sphere", {0.2}}, {"&", {90}},
                            {"f", {-3}}, {"&", {90}}, {"F", {1}}, {"^", {90}},
                            {"disc", {0.5}}});
  std::string svg = svgOf(geometry);
  std::size_t path = svg.find("<path ");
  std::size_t line = svg.find("<line ");
  std::size_t circle = svg.find("<circle ");
  ASSERT_NE(path, std::string::npos);
  ASSERT_NE(line, std::string::npos);
  ASSERT_NE(circle, std::string::npos);
  EXPECT_LT(path, line);
  EXPECT_LT(line, circle);
}

TEST(SvgWriterTest, EmptyGeometryIsAnEmptyPicture) {
  std::string svg = svgOf(Geometry{});
  EXPECT_EQ(checkWellFormed(svg), "");
  EXPECT_EQ(attribute(svg, "viewBox"), "0 0 40 40");
  EXPECT_EQ(countOf(svg, "<line "), 0);
}

TEST(SvgWriterTest, RejectsBadOptions) {
  std::ostringstream out;
  EXPECT_THROW(writeSvg(Geometry{}, out, SvgOptions{.hairline = 0}), std::invalid_argument);
  EXPECT_THROW(writeSvg(Geometry{}, out, SvgOptions{.size = 10, .margin = 20}),
               std::invalid_argument);
  EXPECT_THROW(writeSvg(Geometry{}, out, SvgOptions{.decimals = 9}), std::invalid_argument);
}

}  // namespace
}  // namespace ontogen
