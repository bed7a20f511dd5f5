// The directive table (lang/directives.h) against the parser, the compiler and
// docs/LANGUAGE.md: every row parses and applies where its owner says, an unknown name
// is rejected with the table's list, every range is enforced with the row's message.

#include "lang/directives.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "lang/compiler.h"

namespace ontogen {
namespace {

// The lower-case names that follow `prefix` in `text` (and, when `end` is given, are
// followed by it). No <regex>: GCC 12 warns falsely inside it under the sanitizers.
std::vector<std::string> namesAfter(const std::string& text, const std::string& prefix, char end = 0) {
  std::vector<std::string> names;
  for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
    size_t stop = at + prefix.size();
    while (stop < text.size() && text[stop] >= 'a' && text[stop] <= 'z') ++stop;
    if (stop == at + prefix.size()) continue;
    if (end && (stop >= text.size() || text[stop] != end)) continue;
    names.push_back(text.substr(at + prefix.size(), stop - at - prefix.size()));
  }
  return names;
}

struct Compiled {
  DiagnosticSink sink;
  std::unique_ptr<Program> program;
};

std::unique_ptr<Compiled> compileText(const std::string& text) {
  auto result = std::make_unique<Compiled>();
  result->program = compileSource("test.cell", text, result->sink);
  return result;
}

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// A value the row takes (the first of a few that it accepts), unlike the defaults.
double inside(const Directive& directive) {
  for (double value : {3.0, 0.5, 2.0, 1e-6, 0.0, 1.0})
    if (directive.accepts(value)) return value;
  ADD_FAILURE() << "#" << directive.name << " takes none of the sample values";
  return 0;
}

// The directive as a program writes it, with a value it takes.
std::string sample(const Directive& directive) {
  const std::string head = "#" + std::string(directive.name);
  switch (directive.kind) {
    case DirectiveKind::Define:
      return head + " K 2";
    case DirectiveKind::Number:
    case DirectiveKind::Integer:
      return head + " " + number(inside(directive));
    case DirectiveKind::Flag:
      return head;
    case DirectiveKind::Word:
      return head + " " + std::string(directive.words.back());  // the first is the default
    case DirectiveKind::TimeSignature:
      return head + " 3/8";
    case DirectiveKind::NumberedFile:
      return head + " " + number(inside(directive)) + " \"leaf.obj\"";
    case DirectiveKind::NumberedName:
      return head + " " + number(inside(directive)) + " \"Lead\"";
    case DirectiveKind::Range:
      return head + " K -1 2.5";
  }
  return head;
}

// For a flag, another flag to write before it, so that it changes something.
std::string before(const Directive& directive) {
  if (directive.kind != DirectiveKind::Flag) return "";
  for (const Directive& other : directives())
    if (other.kind == DirectiveKind::Flag && other.name != directive.name) return "#" + std::string(other.name);
  return "";
}

// Everything a directive may set, for one system and the program.
std::string settingsOf(const Program& program, int system) {
  const InterpretSettings& s = program.systems[system].settings;
  std::ostringstream out;
  out << s.angle << ' ' << s.yawAngle << ' ' << s.step << ' ' << s.radius << ' ' << s.radians << ' ' << s.timestep << ' '
      << static_cast<int>(s.music.time) << ' ' << s.music.tempo << ' ' << s.music.ppq << ' ' << s.music.format << ' '
      << s.music.timeSignatureNumerator << '/' << s.music.timeSignatureDenominator << ' ' << s.surfaces.size();
  for (const std::string& name : s.music.trackNames) out << " '" << name << "'";
  return out.str();
}

std::string worldOf(const Program& program) {
  std::ostringstream out;
  out << program.seed << ' ' << program.hasSeed << ' ' << program.until << ' ' << program.dt << ' '
      << program.rateTolerance << ' ' << program.defines.size() << ' ' << program.from << ' '
      << program.framesPerSecond << ' ' << program.speed << ' ' << program.look << ' ' << program.allowsNonfinite;
  for (const std::string& set : program.interpretSets) out << ' ' << set;
  return out.str();
}

TEST(Directives, NamesAreUniqueAndFound) {
  std::set<std::string_view> names;
  for (const Directive& directive : directives()) {
    EXPECT_TRUE(names.insert(directive.name).second) << directive.name;
    EXPECT_EQ(findDirective(directive.name), &directive);
    EXPECT_FALSE(directive.doc.empty()) << directive.name;
    EXPECT_EQ(directive.syntax.rfind("#" + std::string(directive.name), 0), 0u) << directive.syntax;
    EXPECT_EQ(directive.apply == nullptr,
              directive.kind == DirectiveKind::Define || directive.kind == DirectiveKind::Range)
        << directive.name;
    EXPECT_EQ(directive.kind == DirectiveKind::Word, !directive.words.empty()) << directive.name;
    // Every value the compiler checks has a message for when it is out of range: none
    // takes every number, as none takes NaN or an infinity.
    const bool compilerChecks = directive.kind == DirectiveKind::Number || directive.kind == DirectiveKind::Integer ||
                                directive.kind == DirectiveKind::NumberedFile ||
                                directive.kind == DirectiveKind::NumberedName;
    if (compilerChecks) {
      EXPECT_FALSE(directive.rangeError.empty()) << directive.name;
      EXPECT_FALSE(directive.accepts(std::numeric_limits<double>::infinity())) << directive.name;
      EXPECT_FALSE(directive.accepts(std::nan(""))) << directive.name;
    }
  }
  EXPECT_EQ(findDirective("defne"), nullptr);
  EXPECT_EQ(findDirective("Angle"), nullptr);  // names are case-sensitive
  EXPECT_EQ(findDirective(""), nullptr);
}

TEST(Directives, EveryRowParsesAndAppliesAtTheTopLevelAndInABlock) {
  for (const Directive& directive : directives()) {
    if (directive.owner == DirectiveOwner::Notation) continue;  // read by the parser: NotationRowsChangeHowTheTextReads
    if (directive.kind == DirectiveKind::Range) continue;       // sets nothing: ARangeNamesADefineOfItsBlock
    SCOPED_TRACE("#" + std::string(directive.name));
    const std::string first = before(directive);
    auto baseline = compileText(first + "\nlsystem a { axiom A }\n");
    ASSERT_NE(baseline->program, nullptr) << formatDiagnostics(baseline->sink);
    const std::string unchanged = settingsOf(*baseline->program, 0) + " | " + worldOf(*baseline->program);

    auto top = compileText(first + "\n" + sample(directive) + "\nlsystem a { axiom A }\n");
    ASSERT_NE(top->program, nullptr) << formatDiagnostics(top->sink);
    EXPECT_NE(settingsOf(*top->program, 0) + " | " + worldOf(*top->program), unchanged);

    auto block = compileText("lsystem a {\n  " + first + "\n  " + sample(directive) + "\n  axiom A\n}\n");
    ASSERT_NE(block->program, nullptr) << formatDiagnostics(block->sink);
    EXPECT_NE(settingsOf(*block->program, 0) + " | " + worldOf(*block->program), unchanged);
  }
}

// A set's settings written in a block are that block's; the world's hold for the program.
TEST(Directives, TheOwnerDecidesWhereABlocksValueHolds) {
  for (const Directive& directive : directives()) {
    if (directive.kind == DirectiveKind::Define || directive.kind == DirectiveKind::Range ||
        directive.owner == DirectiveOwner::Notation)
      continue;
    SCOPED_TRACE("#" + std::string(directive.name));
    const std::string first = before(directive);
    auto baseline =
        compileText("lsystem a {\n  " + first + "\n  axiom A\n}\nlsystem b {\n  " + first + "\n  axiom B\n}\n");
    auto written = compileText("lsystem a {\n  " + first + "\n  axiom A\n}\nlsystem b {\n  " + first + "\n  " +
                               sample(directive) + "\n  axiom B\n}\n");
    ASSERT_NE(baseline->program, nullptr) << formatDiagnostics(baseline->sink);
    ASSERT_NE(written->program, nullptr) << formatDiagnostics(written->sink);
    const Program& was = *baseline->program;
    const Program& is = *written->program;
    EXPECT_EQ(settingsOf(is, 0), settingsOf(was, 0));  // the other block keeps its own
    if (directive.owner == DirectiveOwner::World) {
      EXPECT_EQ(settingsOf(is, 1), settingsOf(was, 1));
      EXPECT_NE(worldOf(is), worldOf(was));
    } else {
      EXPECT_NE(settingsOf(is, 1), settingsOf(was, 1));
      EXPECT_EQ(worldOf(is), worldOf(was));
    }
  }
}

// `#range NAME LOW HIGH` sets nothing; it must name a #define its block sees and hold
// a range, with the messages pinned at the directive.
TEST(Directives, ARangeNamesADefineOfItsBlock) {
  auto good = compileText("#define K 2\n#range K -1 2.5\nlsystem a {\n  #define J 1\n  #range J 0 4\n  #range K 1 3\n  axiom A\n}\n");
  EXPECT_NE(good->program, nullptr) << formatDiagnostics(good->sink);
  auto unknown = compileText("#define K 2\n#range L 0 1\nlsystem a { axiom A }\n");
  ASSERT_EQ(unknown->program, nullptr);
  EXPECT_NE(formatDiagnostics(unknown->sink).find("test.cell:2:1: error: #range names 'L', which is no #define of its "
                                                  "block or of the top level"),
            std::string::npos)
      << formatDiagnostics(unknown->sink);
  auto empty = compileText("#define K 2\n#range K 3 3\nlsystem a { axiom A }\n");
  ASSERT_EQ(empty->program, nullptr);
  EXPECT_NE(formatDiagnostics(empty->sink).find("test.cell:2:1: error: #range K needs finite numbers LOW < HIGH"),
            std::string::npos)
      << formatDiagnostics(empty->sink);
  auto notNumber = compileText("#define K 2\n#range K 0 K\nlsystem a { axiom A }\n");
  ASSERT_EQ(notNumber->program, nullptr);
  EXPECT_NE(formatDiagnostics(notNumber->sink).find("test.cell:2:12: error: expected the highest value of K"),
            std::string::npos)
      << formatDiagnostics(notNumber->sink);
}

TEST(Directives, AnUnknownNameIsRejectedWithTheTablesList) {
  auto c = compileText("#defne K 1\nlsystem a { axiom A }\n");
  ASSERT_EQ(c->sink.diagnostics().size(), 1u) << formatDiagnostics(c->sink);
  const Diagnostic& error = c->sink.diagnostics()[0];
  EXPECT_EQ(error.message, unknownDirectiveMessage("defne"));
  EXPECT_EQ(error.span.line(), 1);
  EXPECT_EQ(error.span.column(), 1);
  // The list is the table, in its order; the text is pinned as the error table of
  // docs/LANGUAGE.md section 7 quotes it.
  EXPECT_EQ(error.message,
            "unknown directive '#defne' (known: #define, #range, #angle, #yawangle, #length, #radius, #radians, "
            "#degrees, #seed, #until, #from, #fps, #speed, #look, #interpret, #dt, #timestep, #tolerance, #allow, #music, "
            "#tempo, #ppq, #midiformat, #timesig, #track, #surface, #letters)");
  for (const Directive& directive : directives()) {
    EXPECT_NE(error.message.find("#" + std::string(directive.name)), std::string::npos) << directive.name;
    const std::string misspelt = std::string(directive.name) + "s";
    auto wrong = compileText("#" + misspelt + " 1\nlsystem a { axiom A }\n");
    ASSERT_EQ(wrong->sink.diagnostics().size(), 1u) << misspelt;
    EXPECT_EQ(wrong->sink.diagnostics()[0].message, unknownDirectiveMessage(misspelt));
  }
}

// #letters changes how the parser reads axioms and productions: in a block for that
// block, at the top level for every block after it.
TEST(Directives, NotationRowsChangeHowTheTextReads) {
  auto spaced = compileText("lsystem a {\n  axiom FF\n}\n");
  ASSERT_NE(spaced->program, nullptr) << formatDiagnostics(spaced->sink);
  EXPECT_EQ(spaced->program->rootSystem().axiom.size(), 1u);
  for (const std::string text :
       {"lsystem a {\n  #letters\n  axiom FF\n}\n", "#letters\nlsystem a {\n  axiom FF\n}\n"}) {
    auto letters = compileText(text);
    ASSERT_NE(letters->program, nullptr) << formatDiagnostics(letters->sink);
    EXPECT_EQ(letters->program->rootSystem().axiom.size(), 2u) << text;
  }
  // A block's #letters ends with the block.
  auto scoped = compileText("lsystem a {\n  #letters\n  axiom FF\n}\nlsystem b {\n  axiom FF\n}\n");
  ASSERT_NE(scoped->program, nullptr) << formatDiagnostics(scoped->sink);
  EXPECT_EQ(scoped->program->systems[1].axiom.size(), 1u);
}

// Directives of cpfg say what ontogen writes instead.
TEST(Directives, ForeignDirectivesSayWhatToWriteInstead) {
  EXPECT_EQ(unknownDirectiveMessage("ignore"),
            "cpfg's '#ignore' is written 'ignore: A B' (without '#') in an lsystem block");
  EXPECT_EQ(unknownDirectiveMessage("consider"),
            "cpfg's '#consider' is written 'consider: A B' (without '#') in an lsystem block");
  EXPECT_EQ(unknownDirectiveMessage("include"), "cpfg's '#include' is written 'import \"file.cell\"' at the top level");
}

// Values just outside each end of a row's range, and fractions where it takes whole
// numbers, fail with the row's message at the directive; the ends it includes pass.
TEST(Directives, RangesAreEnforcedWithTheRowsMessage) {
  int checked = 0;
  for (const Directive& directive : directives()) {
    if (directive.rangeError.empty()) continue;
    SCOPED_TRACE("#" + std::string(directive.name));
    const DirectiveRange& range = directive.range;
    std::vector<double> refused, taken;
    if (std::isfinite(range.min)) {
      refused.push_back(range.min - 1);
      (range.minOpen ? refused : taken).push_back(range.min);
    }
    if (std::isfinite(range.max)) {
      refused.push_back(range.max + 1);
      (range.maxOpen ? refused : taken).push_back(range.max);
    }
    if (directive.kind != DirectiveKind::Number) refused.push_back(inside(directive) + 0.5);
    const std::string file = directive.kind == DirectiveKind::NumberedFile   ? " \"leaf.obj\""
                             : directive.kind == DirectiveKind::NumberedName ? " \"Lead\""
                                                                             : "";
    for (double value : refused) {
      auto c =
          compileText("#" + std::string(directive.name) + " " + number(value) + file + "\nlsystem a { axiom A }\n");
      ASSERT_EQ(c->sink.diagnostics().size(), 1u) << value << "\n" << formatDiagnostics(c->sink);
      const Diagnostic& error = c->sink.diagnostics()[0];
      EXPECT_EQ(error.message, directive.rangeError) << value;
      EXPECT_EQ(error.span.line(), 1);
      EXPECT_EQ(error.span.column(), 1);
      ++checked;
    }
    for (double value : taken) {
      auto c =
          compileText("#" + std::string(directive.name) + " " + number(value) + file + "\nlsystem a { axiom A }\n");
      EXPECT_FALSE(c->sink.hasErrors()) << value << "\n" << formatDiagnostics(c->sink);
    }
  }
  EXPECT_GE(checked, 18);  // seed, until, dt, tolerance, tempo, ppq, midiformat, track, surface
}

// The kinds the parser checks itself: a word from the row's list, a time signature.
// #track: a channel, then the name in double quotes on the same line.
TEST(Directives, ATrackIsAChannelThenANameInQuotes) {
  auto named = compileText("#track 9 \"Drums\"\nlsystem a {\n  #track 2 \"Pad\"\n  axiom A\n}\n");
  ASSERT_NE(named->program, nullptr) << formatDiagnostics(named->sink);
  const auto& tracks = named->program->rootSystem().settings.music.trackNames;
  EXPECT_EQ(tracks[9], "Drums");  // the top level's, for every block
  EXPECT_EQ(tracks[2], "Pad");
  EXPECT_EQ(tracks[0], "");
  auto nameless = compileText("#track 1\nlsystem a { axiom A }\n");
  ASSERT_EQ(nameless->sink.diagnostics().size(), 1u) << formatDiagnostics(nameless->sink);
  EXPECT_EQ(nameless->sink.diagnostics()[0].message,
            "expected the name in double quotes after the number, as in #track C \"NAME\"");
  EXPECT_EQ(nameless->sink.diagnostics()[0].span.line(), 1);
  EXPECT_EQ(nameless->sink.diagnostics()[0].span.column(), 1);
  auto empty = compileText("#track\nlsystem a { axiom A }\n");
  ASSERT_EQ(empty->sink.diagnostics().size(), 1u) << formatDiagnostics(empty->sink);
  EXPECT_EQ(empty->sink.diagnostics()[0].message, "expected a number and a name after '#track', as in #track C \"NAME\"");
}

TEST(Directives, WordsAndTimeSignaturesAreCheckedAsTheyAreRead) {
  const Directive& music = *findDirective("music");
  auto word = compileText("#music backwards\nlsystem a { axiom A }\n");
  ASSERT_EQ(word->sink.diagnostics().size(), 1u);
  EXPECT_EQ(word->sink.diagnostics()[0].message, "expected " + wordChoices(music) + " after #music, found 'backwards'");
  EXPECT_EQ(wordChoices(music), "'sequential' or 'developmental'");

  const Directive& timesig = *findDirective("timesig");
  EXPECT_EQ(describeRange(timesig.range), "1 to 255");
  for (const char* beats : {"0", "256", "2.5"}) {
    auto c = compileText(std::string("#timesig ") + beats + "/4\nlsystem a { axiom A }\n");
    ASSERT_EQ(c->sink.diagnostics().size(), 1u) << beats;
    EXPECT_EQ(c->sink.diagnostics()[0].message,
              std::string("expected a time signature such as 3/4 after #timesig (beats per bar 1 to 255), found "
                          "number '") +
                  beats + "'");
  }
  for (const char* value : {"0", "3", "128"}) {
    auto c = compileText(std::string("#timesig 3/") + value + "\nlsystem a { axiom A }\n");
    ASSERT_EQ(c->sink.diagnostics().size(), 1u) << value;
    EXPECT_EQ(c->sink.diagnostics()[0].message,
              std::string("expected a note value 1, 2, 4, 8, 16, 32 or 64 below the '/' of #timesig, found number '") +
                  value + "'");
  }
  auto ends = compileText("#timesig 255/64\nlsystem a { axiom A }\n");
  ASSERT_NE(ends->program, nullptr) << formatDiagnostics(ends->sink);
  EXPECT_EQ(ends->program->rootSystem().settings.music.timeSignatureNumerator, 255);
  EXPECT_EQ(ends->program->rootSystem().settings.music.timeSignatureDenominator, 64);
}

TEST(Directives, RangesAreDescribedAsHelpPrintsThem) {
  EXPECT_EQ(describeValues(*findDirective("tempo")), "> 0 and ≤ 1000");
  EXPECT_EQ(describeValues(*findDirective("tolerance")), "> 0 and < 1");
  EXPECT_EQ(describeValues(*findDirective("seed")), "0 to 9007199254740991");
  EXPECT_EQ(describeValues(*findDirective("radius")), "≥ 0");
  EXPECT_EQ(describeValues(*findDirective("ppq")), "1 to 32767");
  EXPECT_EQ(describeValues(*findDirective("angle")), "finite");
  EXPECT_EQ(describeValues(*findDirective("music")), "sequential or developmental");
  EXPECT_EQ(describeValues(*findDirective("timesig")), "N 1 to 255, D 1, 2, 4 ... 64");
}

// docs/LANGUAGE.md section 3.2 names every directive of the table in its grammar and in
// its table of meanings, and no other.
TEST(Directives, LanguageSection32ListsTheSameDirectives) {
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/docs/LANGUAGE.md");
  ASSERT_TRUE(in) << "docs/LANGUAGE.md";
  std::string line, section;
  bool inSection = false;
  while (std::getline(in, line)) {
    if (line.rfind("### 3.2 ", 0) == 0)
      inSection = true;
    else if (inSection && line.rfind("### ", 0) == 0)
      break;
    if (inSection) section += line + "\n";
  }
  ASSERT_FALSE(section.empty());
  std::set<std::string> table;
  for (const Directive& directive : directives()) table.insert(std::string(directive.name));

  std::set<std::string> grammar, rows;
  const size_t open = section.find("```"), close = section.find("```", open + 3);
  ASSERT_NE(close, std::string::npos);
  const std::string ebnf = section.substr(open, close - open);
  for (const std::string& found : namesAfter(ebnf, "\"#", '"')) grammar.insert(found);
  std::istringstream lines(section);
  while (std::getline(lines, line)) {
    if (line.rfind("| `#", 0) != 0) continue;
    const std::string first = line.substr(0, line.find('|', 1));
    for (const std::string& found : namesAfter(first, "`#")) rows.insert(found);
  }
  EXPECT_EQ(grammar, table);
  EXPECT_EQ(rows, table);
}


// A #define whose arithmetic overflows is an error at its value; `inf` itself, or a
// constant that is one, is a value a define may take (a lifetime that never ends).
TEST(Directives, ADefineThatOverflowsIsAnErrorAtItsValue) {
  auto overflow = compileText("#define K 1e308*10\nlsystem a { axiom A }\n");
  ASSERT_EQ(overflow->sink.diagnostics().size(), 1u) << formatDiagnostics(overflow->sink);
  const Diagnostic& error = overflow->sink.diagnostics()[0];
  EXPECT_EQ(error.message,
            "the value of #define K overflows to an infinity (past ±1.8e308); write inf if an infinity is meant");
  EXPECT_EQ(error.span.line(), 1);
  EXPECT_EQ(error.span.column(), 11);
  auto divided = compileText("lsystem a {\n  #define Q 1 / 0\n  axiom A\n}\n");
  ASSERT_EQ(divided->sink.diagnostics().size(), 1u) << formatDiagnostics(divided->sink);
  EXPECT_EQ(divided->sink.diagnostics()[0].span.line(), 2);
  for (const char* meant : {"#define L inf", "#define L -inf", "#define M inf\n#define L 2 * M"}) {
    auto accepted = compileText(std::string(meant) + "\nlsystem a { axiom A }\n");
    EXPECT_FALSE(accepted->sink.hasErrors()) << meant << "\n" << formatDiagnostics(accepted->sink);
  }
}

}  // namespace
}  // namespace ontogen
