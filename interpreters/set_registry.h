#pragma once
// The interpretation sets ontogen knows, by name: one place to make a set for a run
// and to tell the compiler which commands each set accepts.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/environment_process.h"
#include "interpreters/formats/renderer.h"
#include "interpreters/formats/scene_output.h"
#include "interpreters/interpretation_set.h"
#include "lang/compiler.h"
#include "model/program.h"

namespace ontogen {

/// Names of the sets, in the order `ontogen help` lists them.
std::vector<std::string> interpretationSetNames();

/// A new set configured from a system's settings, or null if there is no such set.
std::unique_ptr<InterpretationSet> makeInterpretationSet(std::string_view name, const InterpretSettings& settings);

/// Output settings a run gives the sets (`ontogen run --format --view --size`).
struct SetOptions {
  std::string formats = "glb,png";  ///< geometry: comma-separated formats (geometry_set.h)
  RenderDef render{};               ///< geometry: picture size and view
  UpAxis up = UpAxis::Y;            ///< geometry: the up axis of OBJ and PLY files
  double framesPerSecond = 25;      ///< geometry and image: of the movie (mp4), > 0
  bool sceneNodes = false;          ///< geometry: record the scene's nodes (GeometrySetDef::sceneNodes)
  uint64_t maxMemoryBytes = 0;      ///< dynamics: the memory limit MuJoCo's room counts against (0: none)
};

/// The same, with output settings; throws std::invalid_argument with a message for the
/// user when they are wrong (an unknown format, mp4 without ffmpeg, a bad size).
std::unique_ptr<InterpretationSet> makeInterpretationSet(std::string_view name, const InterpretSettings& settings,
                                                         const SetOptions& options);

/// The output stage's settings from a run's output settings; throws std::invalid_argument
/// with a message for the user when they are wrong.
SceneOutputDef sceneOutputDefOf(const SetOptions& options);

/// What answers a program's query modules (core/environment_process.h): the physics set
/// when it asks ?F, ?M or ?D, otherwise the turtle; null when it has none.
std::shared_ptr<const EnvironmentProcess> queryEnvironmentOf(const Program& program);

/// For the compiler: the commands of every set (the trace set accepts any).
std::vector<CommandSetInfo> commandSets();

}  // namespace ontogen
