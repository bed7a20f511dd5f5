#include "interpreters/set_registry.h"

#include <stdexcept>

#include "interpreters/creature/creature_commands.h"
#include "interpreters/creature/creature_set.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/dynamics/dynamics_set.h"
#include "interpreters/geometry/geometry_set.h"
#include "interpreters/geometry/obj_reader.h"
#include "interpreters/geometry/turtle_commands.h"
#include "interpreters/image/image_set.h"
#include "interpreters/music/music_commands.h"
#include "interpreters/music/music_set.h"
#include "interpreters/physics/physics_commands.h"
#include "interpreters/physics/physics_queries.h"
#include "interpreters/physics/physics_set.h"
#include "interpreters/text/trace_set.h"

namespace ontogen {

std::vector<std::string> interpretationSetNames() { return {"geometry", "creature", "dynamics", "physics", "image", "music", "trace"};
}

SceneOutputDef sceneOutputDefOf(const SetOptions& options) {
  SceneOutputDef def;
  std::string error = applyGeometryFormats(options.formats, def);
  if (!error.empty()) throw std::invalid_argument(error);
  def.render = options.render;
  def.up = options.up;
  def.framesPerSecond = options.framesPerSecond;
  return def;
}

std::unique_ptr<InterpretationSet> makeInterpretationSet(std::string_view name, const InterpretSettings& settings) {
  return makeInterpretationSet(name, settings, SetOptions{.formats = "svg,obj"});
}

std::unique_ptr<InterpretationSet> makeInterpretationSet(std::string_view name, const InterpretSettings& settings,
                                                         const SetOptions& options) {
  if (name == "geometry") {
    GeometrySetDef def;
    def.output = sceneOutputDefOf(options);
    def.sceneNodes = options.sceneNodes;
    def.turtle = turtleDefOf(settings);
    for (const SurfaceFile& file : settings.surfaces) {
      try {
        def.turtle.surfaces[file.id] = loadObjSurface(file.path);
      } catch (const SurfaceError& bad) {
        throw std::invalid_argument((file.location.empty() ? "" : file.location + ": ") + bad.what());
      }
    }
    return std::make_unique<GeometrySet>(def);
  }
  if (name == "creature") {
    CreatureSetDef def;
    def.output = sceneOutputDefOf(options);
    def.radians = settings.radians;
    const SceneOutputDef& out = def.output;
    if (!out.writeSvg && !out.writeObj && !out.writePly && !out.writePngFrames && !out.writeMp4)
      def.meshing = out.writePng ? LimbMeshing::GrownAndLastFrame : LimbMeshing::GrownFrames;
    return std::make_unique<CreatureSet>(def);
  }
  if (name == "dynamics") {
    DynamicsSetDef def;
    const SceneOutputDef out = sceneOutputDefOf(options);
    def.radians = settings.radians;
    def.physics.timestep = settings.timestep;
    def.writeMjcf = out.writeMjcf;
    def.maxMemoryBytes = options.maxMemoryBytes;
    if (!out.writeSvg && !out.writeObj && !out.writePly && !out.writePngFrames && !out.writeMp4)
      def.meshing = out.writePng ? LimbMeshing::GrownAndLastFrame : LimbMeshing::GrownFrames;
    return std::make_unique<DynamicsSet>(def);
  }
  if (name == "physics") {
    PhysicsSetDef def;
    def.output = sceneOutputDefOf(options);
    def.turtle = turtleDefOf(settings);
    return std::make_unique<PhysicsSet>(def);
  }
  if (name == "music") return std::make_unique<MusicSet>(MusicSet::defFrom(settings.music));
  if (name == "trace") return std::make_unique<TraceSet>();
  if (name == "image") {
    SceneOutputDef formats;
    if (std::string error = applyGeometryFormats(options.formats, formats); !error.empty())
      throw std::invalid_argument(error);
    ImageSetDef def;
    def.movie = formats.writeMp4;
    // Pictures unless the movie is all that was asked for.
    def.pictures = formats.writePng || formats.writePngFrames || !formats.writeMp4;
    def.framesPerSecond = options.framesPerSecond;
    return std::make_unique<ImageSet>(def);
  }
  return nullptr;
}

std::shared_ptr<const EnvironmentProcess> queryEnvironmentOf(const Program& program) {
  if (!program.hasQueries) return nullptr;
  const InterpretSettings& settings = program.rootSystem().settings;
  if (asksPhysics(program)) return PhysicsQueries::forSettings(settings);
  return TurtleQueries::forSettings(settings);
}

namespace {
// The compiler's view of a set's command tables (rows with name, minArity, maxArity): a
// lookup by name whose ids number the rows of the tables in order. Tables are static, so
// the infos are too.
template <auto... Tables>
const CommandInfo* findInTable(std::string_view command) {
  static const std::vector<CommandInfo> infos = [] {
    std::vector<CommandInfo> list;
    const auto add = [&list](const auto& table) {
      for (const auto& row : table)
        list.push_back({row.name, row.minArity, row.maxArity, static_cast<int>(list.size())});
    };
    (add(Tables()), ...);
    return list;
  }();
  for (const CommandInfo& info : infos)
    if (info.name == command) return &info;
  return nullptr;
}
}  // namespace

std::vector<CommandSetInfo> commandSets() {
  std::vector<CommandSetInfo> sets;
  sets.push_back({"geometry", findInTable<turtleCommands>,
                  {},
                  // #surface files are read as the run reads them, so check fails where run would.
                  [](const std::string& path) -> std::string {
                    try {
                      loadObjSurface(path);
                    } catch (const SurfaceError& bad) {
                      return bad.what();
                    }
                    return {};
                  }});
  sets.push_back({"creature", findInTable<creatureCommands>});
  // Its own commands, then the creature set's, numbered after them.
  sets.push_back({"dynamics", findInTable<dynamicsCommands, creatureCommands>});
  // Its own commands, then the turtle's, numbered after them.
  sets.push_back({"physics", findInTable<physicsCommands, turtleCommands>});
  sets.push_back({"image", [](std::string_view command) -> const CommandInfo* {
                    static const CommandInfo pixel{"pixel", 3, 3}, range{"range", 2, 2};
                    if (command == "pixel") return &pixel;
                    if (command == "range") return &range;
                    return nullptr;
                  }});
  sets.push_back({"music",
                  findInTable<musicCommands>,
                  musicConstant});
  sets.push_back({"trace", [](std::string_view command) -> const CommandInfo* {
                    static thread_local CommandInfo any;
                    any = {command, 0, -1};
                    return &any;
                  }});
  return sets;
}

}  // namespace ontogen
