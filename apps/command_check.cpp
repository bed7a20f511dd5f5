#include <iostream>

#include "apps/commands.h"
#include "apps/program_loader.h"

namespace ontogen::app {

int runCheck(const CommonOptions& options) {
  LoadedProgram loaded = loadProgram(options);
  if (!loaded.program) return loaded.exitCode;
  const Program& program = *loaded.program;
  size_t declared = 0;
  for (const auto& master : program.masters) declared += master.declared;
  std::cout << options.file << ": ok (" << program.systems.size() << " system"
            << (program.systems.size() == 1 ? "" : "s") << ", " << declared << " developing cell"
            << (declared == 1 ? "" : "s") << ", " << program.masters.size() << " symbols; root '"
            << program.rootSystem().name << "')\n";
  return kExitOk;
}

}  // namespace ontogen::app
