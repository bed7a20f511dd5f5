// The word as text and JSON (interpreters/text/word_text.h): writeWordText, which writes
// a word held compactly as it is held, gives the bytes of the plain path (a
// WordTextWriter streamed by visitWord) on every kind of word; the JSON reads back to the
// captured word's values exactly; numbers take the forms printf's %g and std::to_chars
// give.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/parents.h"
#include "core/word.h"
#include "core/world.h"
#include "interpreters/text/word_text.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

std::string plainText(const World& world, int precision, bool interpreted) {
  std::ostringstream text;
  {
    BufferedOutput out(text);
    WordTextWriter writer(out, precision);
    if (interpreted)
      visitInterpretedWord(world, writer);
    else
      visitWord(world, writer);
  }
  return text.str();
}

std::string fastText(const World& world, int precision, bool interpreted) {
  std::ostringstream text;
  {
    BufferedOutput out(text);
    writeWordText(world, out, precision, interpreted);
  }
  return text.str();
}

std::string readProgram(const std::string& path) {
  std::ifstream in(std::filesystem::path(ONTOGEN_SOURCE_DIR) / path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct Case {
  std::string name;
  std::string program;
  std::vector<double> times;
  bool withIds = false;  // the world keeps its word's ids (WorldDef::wordsWithoutIds off)
};

// Words of every kind: held compactly or as records, with and without ids, with values,
// ages, long labels, non-finite values, nested pools, a grid, a homomorphism's image,
// and Koch at t = 7, whose text (625 KB) spans many of the writer's chunks.
std::vector<Case> cases() {
  const std::string koch = "lsystem koch {\n  axiom F\n  F -> F + F - F - F + F\n}\n";
  const std::string timed =
      "cell AVeryLongLabelIndeed(x = 1) { lifetime 1.5; rules { terminal: -> AVeryLongLabelIndeed(x * 3) B(x / 7) "
      "AVeryLongLabelIndeed(x + 0.5) C; } }\n"
      "cell B(y = 0) { lifetime 2; rules { terminal: -> B(y * -1.5) C B(y + 1e6); } }\n"
      "cell C { }\n"
      "system s { pool linear; axiom AVeryLongLabelIndeed(1) B(2) C; }\n";
  const std::string nonfinite =
      "#allow nonfinite\n"
      "lsystem n {\n  axiom A(1)\n  A(x) -> A(x * 1e300) B(x * 1e300 * 1e300 * 0) B(-x * 1e300) C(-0 * x)\n}\n";
  const std::string grid =
      "cell P(a = 0, b = 0) { rules { a = a + 0.25; b = b - me.x * 1e7; } }\n"
      "system g { pool grid(5, 3) wrap vonneumann; fill P(me.x / 3, me.y); }\n";
  return {
      {"koch", koch, {0, 1, 7}},
      {"koch with ids", koch, {5}, true},
      {"parametric", testing_support::kParametric, {3, 12}},
      {"parametric with ids", testing_support::kParametric, {12}, true},
      {"timed", timed, {0, 2.5, 6.75}},
      {"timed with ids", timed, {6.75}, true},
      {"non-finite", nonfinite, {1, 2}},
      {"nested pools", readProgram("models/orchard.cell"), {0, 2}},
      {"grid", grid, {0, 2}},
      {"homomorphism", readProgram("tests/programs/homomorphism_context_compact_word.cell"), {2, 3}},
  };
}

TEST(WordText, WrittenAsHeldIsThePlainPathToTheByte) {
  for (const Case& c : cases()) {
    auto program = compileOrFail(c.program, c.name + ".cell");
    ASSERT_NE(program, nullptr) << c.name;
    WorldDef def;
    def.seed = 3;
    def.wordsWithoutIds = !c.withIds;
    World world(program, def);
    for (double t : c.times) {
      world.advanceTo(t, 1.0);
      for (int precision : {1, 3, 6, 9, 17})
        for (bool interpreted : {false, true}) {
          const std::string what = c.name + " at t = " + std::to_string(t) + ", precision " +
                                   std::to_string(precision) + (interpreted ? ", interpreted" : "");
          const std::string plain = plainText(world, precision, interpreted);
          EXPECT_EQ(fastText(world, precision, interpreted), plain) << what;
          if (c.name == "non-finite" && t == 2 && precision == 6) {
            EXPECT_EQ(plain, "A(inf) B(nan) B(-inf) C(0) B(nan) B(-1e+300) C(0)") << what;
          }
        }
    }
  }
}

// Every value of the JSON reads back to the captured word's, to the bit; infinities and
// NaN as null, the nested pools in their system cells.
void expectReadsBack(const nlohmann::json& cells, const std::vector<WordCell>& word, const std::string& what) {
  ASSERT_EQ(cells.size(), word.size()) << what;
  auto same = [&](const nlohmann::json& value, double expected, const std::string& field) {
    if (!std::isfinite(expected)) {
      EXPECT_TRUE(value.is_null()) << what << ": " << field;
    } else {
      ASSERT_TRUE(value.is_number()) << what << ": " << field;
      EXPECT_EQ(std::bit_cast<uint64_t>(value.get<double>() + 0.0), std::bit_cast<uint64_t>(expected + 0.0))
          << what << ": " << field << " " << value.dump() << " for " << expected;
    }
  };
  auto sameArray = [&](const nlohmann::json& values, const std::vector<double>& expected, const std::string& field) {
    ASSERT_EQ(values.size(), expected.size()) << what << ": " << field;
    for (size_t k = 0; k < expected.size(); ++k) same(values[k], expected[k], field);
  };
  for (size_t i = 0; i < word.size(); ++i) {
    const nlohmann::json& cell = cells[i];
    const WordCell& expected = word[i];
    EXPECT_EQ(cell["label"].get<std::string>(), expected.label) << what;
    sameArray(cell["params"], expected.params, "params");
    sameArray(cell["developed"], expected.developed, "developed");
    same(cell["age"], expected.age, "age");
    same(cell["id"], idValue(expected.id), "id");
    if (expected.parent == kNoParent)
      EXPECT_EQ(cell["parent"].get<int>(), -1) << what;
    else
      same(cell["parent"], idValue(expected.parent), "parent");
    if (!expected.position.empty()) sameArray(cell["position"], expected.position, "position");
    EXPECT_EQ(cell.contains("pool"), expected.system) << what;
    if (expected.system) expectReadsBack(cell["pool"], expected.pool, what + " in " + expected.label);
  }
}

TEST(WordJson, ReadsBackToTheCapturedWord) {
  for (const Case& c : cases()) {
    auto program = compileOrFail(c.program, c.name + ".cell");
    ASSERT_NE(program, nullptr) << c.name;
    WorldDef def;
    def.seed = 3;
    def.wordsWithoutIds = !c.withIds;
    World world(program, def);
    std::vector<WordAtTime> words;
    for (double t : c.times) {
      world.advanceTo(t, 1.0);
      words.push_back({world.time(), captureWord(world)});
    }
    // The streaming writer, as `ontogen word --json` drives it, and the one of captured words.
    std::ostringstream streamed;
    {
      BufferedOutput out(streamed);
      WordJsonWriter writer(out);
      writer.begin();
      writer.beginTime(world.time(), true);
      visitWord(world, writer);
      writer.endTime();
      writer.end();
    }
    std::ostringstream captured;
    writeWordJson(captured, {words.back()});
    EXPECT_EQ(streamed.str(), captured.str()) << c.name;
    std::ostringstream all;
    writeWordJson(all, words);
    const nlohmann::json document = nlohmann::json::parse(all.str());
    ASSERT_EQ(document["times"].size(), words.size()) << c.name;
    for (size_t k = 0; k < words.size(); ++k)
      expectReadsBack(document["times"][k]["cells"], words[k].cells, c.name + " at t = " + std::to_string(words[k].time));
  }
}

// The compact JSON of one time as `ontogen word --json=compact` streams it: a word held
// without ids written as held (CompactWordJsonWriter::writeWord), or cell by cell.
std::string compactJson(const World& world, bool asHeld, bool interpreted = false) {
  std::ostringstream text;
  {
    BufferedOutput out(text);
    CompactWordJsonWriter writer(out);
    writer.begin();
    writer.beginTime(world.time(), true);
    if (asHeld)
      writer.writeWord(world, interpreted);
    else if (interpreted)
      visitInterpretedWord(world, writer);
    else
      visitWord(world, writer);
    writer.endTime();
    writer.end();
  }
  return text.str();
}

// The compact form's cells are the full form's less its defaults: a bare string is a
// label alone; "params" absent is none, "developed" absent is "params", "age" is there
// for timed cells alone; no ids, no parents.
void expectCompactReadsBack(const nlohmann::json& cells, const std::vector<WordCell>& word, const std::string& what) {
  ASSERT_TRUE(cells.is_array()) << what;
  ASSERT_EQ(cells.size(), word.size()) << what;
  auto sameArray = [&](const nlohmann::json& values, const std::vector<double>& expected, const std::string& field) {
    ASSERT_EQ(values.size(), expected.size()) << what << ": " << field;
    for (size_t k = 0; k < expected.size(); ++k) {
      if (!std::isfinite(expected[k]))
        EXPECT_TRUE(values[k].is_null()) << what << ": " << field;
      else
        EXPECT_EQ(std::bit_cast<uint64_t>(values[k].get<double>() + 0.0), std::bit_cast<uint64_t>(expected[k] + 0.0))
            << what << ": " << field;
    }
  };
  for (size_t i = 0; i < word.size(); ++i) {
    const nlohmann::json& cell = cells[i];
    const WordCell& expected = word[i];
    const bool alone = expected.params.empty() && expected.developed.empty() && !expected.timed &&
                       expected.position.empty() && !expected.system;
    if (alone) {
      ASSERT_TRUE(cell.is_string()) << what << ": " << cell.dump();
      EXPECT_EQ(cell.get<std::string>(), expected.label) << what;
      continue;
    }
    ASSERT_TRUE(cell.is_object()) << what << ": " << cell.dump();
    EXPECT_EQ(cell["label"].get<std::string>(), expected.label) << what;
    EXPECT_FALSE(cell.contains("id")) << what;
    EXPECT_FALSE(cell.contains("parent")) << what;
    EXPECT_EQ(cell.contains("params"), !expected.params.empty()) << what;
    const nlohmann::json params = cell.contains("params") ? cell["params"] : nlohmann::json::array();
    sameArray(params, expected.params, "params");
    sameArray(cell.contains("developed") ? cell["developed"] : params, expected.developed, "developed");
    ASSERT_EQ(cell.contains("age"), expected.timed) << what;
    if (expected.timed) sameArray(nlohmann::json::array({cell["age"]}), {expected.age}, "age");
    EXPECT_EQ(cell.contains("position"), !expected.position.empty()) << what;
    if (!expected.position.empty()) sameArray(cell["position"], expected.position, "position");
    EXPECT_EQ(cell.contains("pool"), expected.system) << what;
    if (expected.system) expectCompactReadsBack(cell["pool"], expected.pool, what + " in " + expected.label);
  }
}

TEST(CompactWordJson, ReadsBackToTheCapturedWord) {
  for (const Case& c : cases()) {
    auto program = compileOrFail(c.program, c.name + ".cell");
    ASSERT_NE(program, nullptr) << c.name;
    WorldDef def;
    def.seed = 3;
    def.wordsWithoutIds = !c.withIds;
    // Streamed from one world, captured from another: capturing gives a word its ids.
    World streamed(program, def), captured(program, def);
    std::vector<WordAtTime> words;
    for (double t : c.times) {
      streamed.advanceTo(t, 1.0);
      captured.advanceTo(t, 1.0);
      const std::string what = c.name + " at t = " + std::to_string(t);
      for (bool interpreted : {false, true}) {
        const std::string asHeld = compactJson(streamed, true, interpreted);
        EXPECT_EQ(asHeld, compactJson(streamed, false, interpreted)) << what << (interpreted ? ", interpreted" : "");
        const nlohmann::json document = nlohmann::json::parse(asHeld);
        EXPECT_EQ(document["form"], "compact") << what;
        ASSERT_EQ(document["times"].size(), 1u) << what;
        EXPECT_EQ(document["times"][0]["t"].get<double>(), streamed.time()) << what;
        expectCompactReadsBack(document["times"][0]["cells"],
                               interpreted ? captureInterpretedWord(captured) : captureWord(captured),
                               what + (interpreted ? ", interpreted" : ""));
      }
      words.push_back({captured.time(), captureWord(captured)});
    }
    std::ostringstream all;
    writeCompactWordJson(all, words);
    const nlohmann::json document = nlohmann::json::parse(all.str());
    ASSERT_EQ(document["times"].size(), words.size()) << c.name;
    for (size_t k = 0; k < words.size(); ++k)
      expectCompactReadsBack(document["times"][k]["cells"], words[k].cells,
                             c.name + " at t = " + std::to_string(words[k].time) + ", captured");
  }
}

TEST(CompactWordJson, GoldenWords) {
  const std::string koch = "lsystem koch {\n  axiom F\n  F -> F + F - F - F + F\n}\n";
  World kochWorld(compileOrFail(koch, "koch.cell"), WorldDef{});
  kochWorld.advanceTo(1, 1.0);
  EXPECT_EQ(compactJson(kochWorld, true),
            "{\"form\": \"compact\", \"times\": [\n  {\"t\": 1, \"cells\": "
            "[\"F\",\"+\",\"F\",\"-\",\"F\",\"-\",\"F\",\"+\",\"F\"]}\n]}\n");
  World parametric(compileOrFail(testing_support::kParametric, "parametric.cell"), WorldDef{});
  parametric.advanceTo(2, 1.0);
  EXPECT_EQ(compactJson(parametric, true),
            "{\"form\": \"compact\", \"times\": [\n  {\"t\": 2, \"cells\": [{\"label\": \"A\", \"params\": [3]},"
            "{\"label\": \"B\", \"params\": [1]},{\"label\": \"B\", \"params\": [1.5]},"
            "{\"label\": \"B\", \"params\": [0.25]}]}\n]}\n");
  // Labels that JSON escapes, a timed cell's age, and a label too long to be copied whole.
  const std::string timed =
      "cell Q(x = 1) { lifetime 2; rules { terminal: -> Q(x) LongerThanSixteenBytes; } }\n"
      "cell LongerThanSixteenBytes { }\n"
      "system s { pool linear; axiom Q(0.5) LongerThanSixteenBytes; }\n";
  World timedWorld(compileOrFail(timed, "timed.cell"), WorldDef{});
  timedWorld.advanceTo(2.5, 0.5);
  EXPECT_EQ(compactJson(timedWorld, true),
            "{\"form\": \"compact\", \"times\": [\n  {\"t\": 2.5, \"cells\": [{\"label\": \"Q\", \"params\": [0.5], "
            "\"age\": 0.5},\"LongerThanSixteenBytes\",\"LongerThanSixteenBytes\"]}\n]}\n");
}

// The shortest form that reads back is std::to_chars's, whole numbers included: digits
// up to four trailing zeros, the exponent form from five on (a tie goes to the digits).
TEST(WordJson, NumbersAreTheShortestFormThatReadsBack) {
  std::vector<double> values = {1, -1, 7, 10, 100, 1000, 10000, 99999, 100000, -100000, 120000, 1234500000,
                                123456789012345678.0, 9007199254740991.0, 9007199254740992.0, 9007199254740993.0,
                                4503599627370497.0, -4503599627370497.0, 0.5, -0.25, 1e-7, 1e21, 1e22, 3e15, 1e15,
                                std::nextafter(1.0, 2.0), std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::denorm_min()};
  for (double scale = 1; scale < 1e17; scale *= 7) values.push_back(std::round(scale * 1.37));
  // Every count of digits an id has, at its bounds and with zeros inside.
  for (double power = 1; power <= 1e15; power *= 10)
    for (double v : {power, power - 1, power + 1, 2 * power + 3, 9 * power + power / 10 + 7})
      if (v >= 1) values.push_back(v);
  for (double v : {1234567890123456.0, 9876543210987654.0, 1000000000000001.0, 1000000010000000.0, 100000000.0,
                   99999999.0, 4000000012345678.0})
    values.push_back(v);
  for (double v : values) {
    char expected[64];
    const auto end = std::to_chars(expected, expected + sizeof expected, v);
    EXPECT_EQ(formatExact(v), std::string(expected, end.ptr)) << v;
  }
  EXPECT_EQ(formatExact(0.0), "0");
  EXPECT_EQ(formatExact(-0.0), "0");
  EXPECT_EQ(formatExact(std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(formatExact(std::nan("")), "null");
}

// The text's numbers are printf's %.*g (without -0), whole numbers included.
TEST(WordText, NumbersArePrintfsShortForm) {
  const std::vector<double> values = {1, -1, 12, 999999, 1000000, -1000000, 1234567, 12345678, 100, 0.5, -2.75,
                                      1e16, 9999999999999998.0, 12345678901234568.0, -4503599627370497.0,
                                      123456789012345678.0, 100000000, 99999999, 100000001, 1e-5, 3.14159265358979, 2e300};
  for (int precision : {1, 2, 3, 6, 9, 15, 17})
    for (double v : values) {
      WordCell cell;
      cell.label = "X";
      cell.params = cell.developed = {v};
      char expected[64];
      std::snprintf(expected, sizeof expected, "X(%.*g)", precision, v);
      EXPECT_EQ(formatWord({cell}, precision), expected) << v << " at precision " << precision;
    }
}

}  // namespace
}  // namespace ontogen
