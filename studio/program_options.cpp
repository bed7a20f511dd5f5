#include "studio/program_options.h"

#include "interpreters/set_registry.h"

namespace ontogen::studio {

StudioSource readStudioSource(const StudioProgramOptions& options, const WorldLimits& limits) {
  if (options.read) return options.read(options.file, options.maxSourceBytes, limits);
  SourceText read = readSourceFile(options.file, options.maxSourceBytes);
  return {std::move(read.text), options.file, std::move(read.error), nullptr, {}};
}

WorldDef worldDefOf(const StudioProgramOptions& options, const Program& program) {
  WorldDef def;
  def.seed = options.seed.value_or(program.seed);
  def.limits = options.limits;
  def.threads = options.threads;
  // Query modules are answered by the turtle, as the geometry set draws the word, or by
  // the physics set's solve.
  def.environment = queryEnvironmentOf(program);
  return def;
}

}  // namespace ontogen::studio
