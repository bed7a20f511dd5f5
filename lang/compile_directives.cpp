// A block's directives: interpretation settings (`#angle`, `#music` ...) into the
// block's InterpretSettings, program-wide ones (`#seed`, `#until`, `#dt`, `#tolerance`)
// into the program. #define is a constant (lang/compile_functions.cpp).

#include <cmath>
#include <filesystem>
#include <string>

#include "lang/compile_stages.h"
#include "lang/expression_compiler.h"

namespace ontogen::detail {

void compileDirectives(CompileContext& ctx, const std::vector<ast::Setting>& list, InterpretSettings& target,
                       const Scope& scope) {
  for (const auto& setting : list) {
    if (setting.name == "radians") {
      target.radians = true;
      continue;
    }
    if (setting.name == "degrees") {
      target.radians = false;
      continue;
    }
    if (setting.name == "music") {
      target.music.time = setting.word == "developmental" ? MusicTime::Developmental : MusicTime::Sequential;
      continue;
    }
    if (setting.name == "timesig") {
      target.music.timeSignatureNumerator = setting.numerator;
      target.music.timeSignatureDenominator = setting.denominator;
      continue;
    }
    auto value = evaluateConstant(*setting.value, ctx.constantLookup(scope), ctx.sink, "#" + setting.name);
    if (!value) continue;
    if (setting.name == "surface") {
      if (*value < 0 || *value > 1023 || *value != std::floor(*value)) {
        ctx.sink.error(setting.span,
                       "#surface takes a whole number 0 to 1023 before the file, as in #surface 1 \"bud.obj\"");
        continue;
      }
      SurfaceFile file{static_cast<int>(*value), setting.word, ""};
      if (setting.span.valid()) {
        const std::filesystem::path base = std::filesystem::path(setting.span.file->name()).parent_path();
        if (std::filesystem::path(file.path).is_relative()) file.path = (base / file.path).lexically_normal().string();
        file.location = setting.span.file->name() + ":" + std::to_string(setting.span.line()) + ":" +
                        std::to_string(setting.span.column());
      }
      target.surfaces.push_back(std::move(file));
      continue;
    }
    if (setting.name == "angle") {
      target.angle = *value;
      target.yawAngle = *value;
    } else if (setting.name == "yawangle") {
      target.yawAngle = *value;
    } else if (setting.name == "length") {
      target.step = *value;
    } else if (setting.name == "until") {
      if (!(*value > 0))
        ctx.sink.error(setting.span, "#until must be greater than 0");
      else
        ctx.program->until = *value;
    } else if (setting.name == "dt") {
      if (!(*value > 0))
        ctx.sink.error(setting.span, "#dt must be greater than 0");
      else
        ctx.program->dt = *value;
    } else if (setting.name == "tolerance") {
      if (!(*value > 0) || *value >= 1)
        ctx.sink.error(setting.span, "#tolerance is between 0 and 1, as in 1e-6");
      else
        ctx.program->rateTolerance = *value;
    } else if (setting.name == "tempo") {
      if (!(*value > 0) || *value > 1000)
        ctx.sink.error(setting.span, "#tempo is in quarter notes per minute, above 0 and at most 1000");
      else
        target.music.tempo = *value;
    } else if (setting.name == "ppq") {
      if (*value < 1 || *value > 32767 || *value != std::floor(*value))
        ctx.sink.error(setting.span, "#ppq must be a whole number of ticks per quarter note, 1 to 32767");
      else
        target.music.ppq = static_cast<int>(*value);
    } else if (setting.name == "midiformat") {
      if (*value != 0 && *value != 1)
        ctx.sink.error(setting.span, "#midiformat must be 0 (one track) or 1 (a track per channel)");
      else
        target.music.format = static_cast<int>(*value);
    } else if (setting.name == "radius") {
      target.radius = *value;
    } else if (setting.name == "seed") {
      if (*value < 0 || *value != std::floor(*value)) {
        ctx.sink.error(setting.span, "#seed must be a whole number ≥ 0");
        continue;
      }
      ctx.program->seed = static_cast<uint64_t>(*value);
      ctx.program->hasSeed = true;
    }
  }
}

}  // namespace ontogen::detail
