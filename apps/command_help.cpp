#include <iomanip>
#include <iostream>
#include <string>
#include <string_view>

#include "apps/commands.h"
#include "apps/program_loader.h"
#include "interpreters/creature/creature_commands.h"
#include "interpreters/geometry/turtle_commands.h"
#include "interpreters/music/music_commands.h"
#include "interpreters/set_registry.h"
#include "lang/builtins.h"
#include "lang/directives.h"

namespace ontogen::app {

namespace {

// `text` and the spaces that fill it to `width` columns (a column per code point, so
// "≥" takes one), at least two.
std::string padded(std::string_view text, size_t width) {
  size_t columns = 0;
  for (unsigned char c : text) columns += (c & 0xC0) != 0x80;
  return std::string(text) + std::string(columns + 2 > width ? 2 : width - columns, ' ');
}

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

}  // namespace

int runHelp() {
  std::cout << "ontogen: grows cell-language programs and realises them as geometry, music and text.\n\n"
               "Commands:\n"
               "  ontogen check FILE                    parse and check a program\n"
               "  ontogen run FILE [options]            develop and write one output per frame\n"
               "  ontogen word FILE --at T1,T2 [--json] print the derivation word at those times\n"
               "  ontogen timeline FILE --out F.svg     draw the time-state diagram of the development\n"
               "  ontogen midi-ports                    list the MIDI output ports for --midi-port\n"
               "  ontogen convert FILE.l|FILE.lpy       print a cpfg or L-Py L-system as a cell-language program\n"
               "  ontogen help                          this text\n"
               "\n"
               "check, run, word and timeline take --define NAME=VALUE (repeatable): the program\n"
               "runs as if its #define NAME said the number VALUE. They also read cpfg (.l) and\n"
               "L-Py (.lpy) files, converted first as ontogen convert prints them.\n\n"
               "Interpretation sets:";
  for (const auto& name : interpretationSetNames()) std::cout << " " << name;
  std::cout << "\n\nTurtle commands (set 'geometry'):\n";
  // The space after the column keeps long signatures (blend, obstaclebox) apart from their doc.
  for (const TurtleCommand& command : turtleCommands())
    std::cout << "  " << std::left << std::setw(16) << command.signature << command.doc << "\n";
  std::cout << "\nCreature commands (set 'creature'; angles in deg, lengths in units):\n";
  for (const CreatureCommand& command : creatureCommands())
    std::cout << "  " << std::left << std::setw(16) << command.signature << "  " << command.doc << "\n";
  std::cout << "\nPlayer commands (set 'music'; pitches in MIDI notes, times in beats):\n";
  for (const MusicCommand& command : musicCommands())
    std::cout << "  " << std::left << std::setw(16) << command.signature << command.doc << "\n";
  std::cout << "\nFunctions:\n";
  for (const BuiltinFunction& function : builtinFunctions())
    std::cout << "  " << std::left << std::setw(22) << function.signature << function.doc << "\n";
  std::cout << "  " << std::left << std::setw(22) << "if(c, a, b)" << "a if c is not 0, else b (only one is evaluated)\n";
  std::cout << "\nConstants:\n";
  for (const BuiltinConstant& constant : builtinConstants())
    std::cout << "  " << std::left << std::setw(22) << constant.name << constant.doc << "\n";
  printDirectives();
  return kExitOk;
}

}  // namespace ontogen::app
