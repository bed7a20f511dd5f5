#pragma once
// The model the studio shows: one program file, re-grown whenever its text changes on
// disk or a `#define` slider moves. Each growth runs the same Run (interpreters/run.h)
// `ontogen run --format glb` does, into the studio's own folder, and keeps what the page
// asks for: the .glb bytes, the diagnostics at their lines, the defines with the ranges
// their sliders span (lang/variation.h), and the music set's notes in seconds.
//
// A growth that fails keeps the last model that grew: the page shows the diagnostics over
// the old model, as an editor keeps the last good build while the text is broken.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "studio/program_options.h"

namespace ontogen::studio {

struct StudioModelDef {
  StudioProgramOptions program;  ///< the file, seed, limits, threads, define values to start from
  std::optional<double> until;   ///< empty: the program's #until
  std::optional<int> frames;     ///< empty: the program's #fps, else kDefaultFrames
  std::filesystem::path work;    ///< a folder of the studio's own for the outputs
};

/// Frames of a model without #fps: enough to scrub through its growth smoothly.
inline constexpr int kDefaultStudioFrames = 60;

/// A define as its slider shows it.
struct StudioDefine {
  std::string name;
  double value = 0;    ///< in effect now
  double written = 0;  ///< as the text writes it
  double low = 0, high = 0;
  bool integer = false;
  int line = 0;
};

/// A note of the music set, in seconds of the page's clock (developmental time for music
/// that follows the development; the score's tempo otherwise).
struct StudioNote {
  double start = 0, duration = 0;
  int channel = 0, pitch = 60, velocity = 100;
};

class StudioModel {
 public:
  explicit StudioModel(StudioModelDef def);

  /// Grows the model again when its file changed since the last growth (time or size or
  /// text); true when it did.
  bool refresh();
  /// Gives a define a value (clamped to nothing: any finite number) and grows again.
  /// False, with nothing changed, when the program has no such define.
  bool setDefine(const std::string& name, double value);
  /// Reads, compiles and grows now.
  void regrow();

  /// Counts every growth, failed or not.
  uint64_t version() const { return version_; }
  /// Counts growths that gave a model: the version of glb().
  uint64_t modelVersion() const { return modelVersion_; }
  /// The last model that grew, as the command line writes it; empty before one did.
  const std::string& glb() const { return glb_; }
  /// The program text read at the last growth.
  const std::string& text() const { return text_; }
  /// The file's name without folder and extension: names the outputs.
  const std::string& stem() const { return stem_; }
  /// The values in effect for the defines the text writes.
  std::map<std::string, double> defineValues() const;
  const std::vector<StudioDefine>& defines() const { return defines_; }
  const std::vector<StudioNote>& notes() const { return notes_; }
  const StudioModelDef& def() const { return def_; }

  /// What the page polls: versions, diagnostics, defines, times, the source.
  nlohmann::json state() const;

 private:
  struct Diagnostic {
    std::string severity;
    int line = 0, column = 0;
    std::string message, formatted;
  };
  struct FileStamp {
    std::filesystem::file_time_type time{};
    uintmax_t size = 0;
    bool operator==(const FileStamp&) const = default;
  };
  std::optional<FileStamp> stampOf() const;
  void grow();

  StudioModelDef def_;
  std::map<std::string, double> overrides_;  // from the sliders and --define
  std::optional<FileStamp> stamp_;
  std::string text_;
  std::string stem_;
  std::vector<StudioDefine> defines_;
  std::vector<Diagnostic> diagnostics_;
  std::vector<StudioNote> notes_;
  std::string glb_;
  uint64_t version_ = 0;
  uint64_t modelVersion_ = 0;
  double from_ = 0, until_ = 0;
  uint64_t cells_ = 0;
  double wallSeconds_ = 0;
};

}  // namespace ontogen::studio
