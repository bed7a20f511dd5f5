// `ontogen convert FILE`: a cpfg (.l) or L-Py (.lpy) file as a cell-language program on
// standard output (lang/convert/convert.h).

#include <iostream>

#include "apps/commands.h"
#include "apps/program_loader.h"
#include "lang/convert/convert.h"

namespace ontogen::app {

int runConvert(const ConvertOptions& options) {
  if (!convert::dialectOfPath(options.file)) {
    std::cerr << "ontogen: error: convert reads cpfg files (.l) and L-Py files (.lpy), not '" << options.file << "'\n";
    return kExitUsage;
  }
  ProgramText text = readProgramText(options.file);
  if (!text.text) return text.exitCode;
  std::cout << *text.text;
  return kExitOk;
}

}  // namespace ontogen::app
