#include <iostream>
#include <utility>
#include <string>
#include <string_view>

#include "apps/commands.h"
#include "apps/program_loader.h"
#include "editors/command_reference.h"
#include "editors/text_mate_grammar.h"
#include "interpreters/creature/creature_commands.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/geometry/turtle_commands.h"
#include "interpreters/music/music_commands.h"
#include "interpreters/physics/physics_commands.h"
#include "interpreters/set_registry.h"
#include "interpreters/sweep/measure.h"
#include "model/builtins.h"
#include "lang/directives.h"
#include "lang/keywords.h"

namespace ontogen::app {

namespace {

// `text` and the spaces that fill it to `width` columns (a column per code point, so
// "≥" takes one), at least two.
std::string padded(std::string_view text, size_t width) {
  size_t columns = 0;
  for (unsigned char c : text) columns += (c & 0xC0) != 0x80;
  return std::string(text) + std::string(columns + 2 > width ? 2 : width - columns, ' ');
}

// One row of a table: the name in a column of `width`, then its doc. A name too long
// for the column puts its doc on the next line, under the column, never against it.
void printRow(std::string_view name, std::string_view doc, size_t width) {
  size_t columns = 0;
  for (unsigned char c : name) columns += (c & 0xC0) != 0x80;
  std::cout << "  " << name;
  if (columns + 2 > width) std::cout << "\n  " << std::string(width, ' ');
  else std::cout << std::string(width - columns, ' ');
  std::cout << doc << "\n";
}

// The column of the command tables, wide enough for all but the longest signatures.
constexpr size_t kSignatureColumn = 22;

void printDirectives() {
  std::cout << "\nDirectives (docs/LANGUAGE.md section 3.2), by the settings they belong to:\n";
  for (DirectiveOwner owner : {DirectiveOwner::Constants, DirectiveOwner::World, DirectiveOwner::Geometry,
                               DirectiveOwner::Music, DirectiveOwner::Notation}) {
    std::cout << "  " << directiveOwnerName(owner) << "\n";
    for (const Directive& directive : directives()) {
      if (directive.owner != owner) continue;
      std::cout << "    " << padded(directive.syntax, 24) << padded(directiveKindName(directive.kind), 16)
                << padded(describeValues(directive), 30) << directive.doc << "\n";
    }
  }
}

void printKeywords() {
  std::cout << "\nKeywords (contextual: elsewhere they are names) and the values every cell reads:\n";
  for (KeywordKind kind : {KeywordKind::Declaration, KeywordKind::Statement, KeywordKind::Reference}) {
    std::cout << "  " << keywordKindName(kind) << "\n";
    for (const Keyword& keyword : keywords())
      if (keyword.kind == kind) std::cout << "  " << padded(keyword.name, kSignatureColumn + 2) << keyword.doc << "\n";
  }
}

}  // namespace

int runHelp(const HelpOptions& options) {
  if (options.grammar) {
    std::cout << editors::textMateGrammar();
    return kExitOk;
  }
  if (options.reference) {
    std::cout << editors::commandReference();
    return kExitOk;
  }
  std::cout << "ontogen: grows cell-language programs and realises them as geometry, music and text.\n\n"
               "Commands:\n";
  constexpr std::pair<std::string_view, std::string_view> kUsage[] = {
      {"ontogen check FILE", "parse and check a program"},
      {"ontogen run FILE [options]", "develop and write one output per frame"},
      {"ontogen word FILE --at T1,T2 [--json[=compact]]", "print the derivation word at those times"},
      {"ontogen statics FILE [--at T] [--json]", "solve the rods' statics (physics set) at a time"},
      {"ontogen timeline FILE --out F.svg", "draw the time-state diagram of the development"},
      {"ontogen sweep FILE --out DIR [options]", "every combination of --define lists and --seeds, measured"},
      {"ontogen evolve FILE --out DIR [opts]", "evolve #define values for the first --measure"},
      {"ontogen studio FILE [--port N]", "a live page at 127.0.0.1: the model re-grown as it is saved"},
      {"ontogen midi-ports", "list the MIDI output ports for --midi-port"},
      {"ontogen convert FILE.l|FILE.lpy", "print a cpfg or L-Py L-system as a cell-language program"},
      {"ontogen help", "this text"},
      {"ontogen help --grammar", "the cell language's TextMate grammar (JSON) for editors"},
      {"ontogen help --reference", "the sets' commands as Markdown (docs/COMMANDS.md)"},
      {"ontogen --version", "the version"},
      {"ontogen COMMAND --help", "the options of a command"},
  };
  for (const auto& [usage, doc] : kUsage) printRow(usage, doc, 40);
  std::cout << "\n"
               "check, run, word, statics and timeline take --define NAME=VALUE (repeatable): the program\n"
               "runs as if its #define NAME said the number VALUE; --max-errors N (default 20,\n"
               "0: all) and --max-source MIB (default 16) bound the check. They also read cpfg (.l)\n"
               "and L-Py (.lpy) files, converted first as ontogen convert prints them.\n\n"
               "sweep and evolve measure each variant with --measure NAME=EXPR over these quantities\n"
               "and count(LABEL), with + - * / ^ ( ) abs sqrt exp log min max (docs/SWEEPS.md):\n";
  for (const QuantityInfo& quantity : quantities()) printRow(quantity.name, quantity.doc, kSignatureColumn);
  std::cout << "\nInterpretation sets:";
  for (const auto& name : interpretationSetNames()) std::cout << " " << name;
  std::cout << "\n\nTurtle commands (set 'geometry'):\n";
  for (const TurtleCommand& command : turtleCommands()) printRow(command.signature, command.doc, kSignatureColumn);
  std::cout << "\nCreature commands (set 'creature'; angles in deg, lengths in units):\n";
  for (const CreatureCommand& command : creatureCommands()) printRow(command.signature, command.doc, kSignatureColumn);
  std::cout << "\nPhysics commands (set 'physics', with every turtle command; SI units: m, kg, N):\n";
  for (const PhysicsCommand& command : physicsCommands()) printRow(command.signature, command.doc, kSignatureColumn);
  std::cout << "\nDynamics commands (set 'dynamics', with every creature command; simulated on MuJoCo):\n";
  for (const DynamicsCommand& command : dynamicsCommands()) printRow(command.signature, command.doc, kSignatureColumn);
  std::cout << "\nPlayer commands (set 'music'; pitches in MIDI notes, times in beats):\n";
  for (const MusicCommand& command : musicCommands()) printRow(command.signature, command.doc, kSignatureColumn);
  std::cout << "\nFunctions:\n";
  for (const BuiltinFunction& function : builtinFunctions())
    printRow(function.signature, function.doc, kSignatureColumn);
  printRow("if(c, a, b)", "a if c is not 0, else b (only one is evaluated)", kSignatureColumn);
  std::cout << "\nConstants:\n";
  for (const BuiltinConstant& constant : builtinConstants()) printRow(constant.name, constant.doc, kSignatureColumn);
  printKeywords();
  printDirectives();
  return kExitOk;
}

}  // namespace ontogen::app
