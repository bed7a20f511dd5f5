#pragma once
// The model the studio shows: one program file, re-grown whenever its text changes on
// disk or a `#define` slider moves. Each growth runs the same Run (interpreters/run.h)
// `ontogen run --format glb` does, into the studio's own folder, and keeps what the page
// asks for: the .glb bytes, the diagnostics at their lines, the defines with the ranges
// their sliders span (lang/variation.h), and the music set's notes in seconds.
//
// The model follows every file it reads: the program file, the files it imports (at any
// depth) and the OBJ files its #surface directives name; a change of any of them grows it
// again (refresh()). Each diagnostic names the file it belongs to, so the page marks in
// the program only the program's own.
//
// Growth runs on a thread of the model's own (start()), never on the thread that asks
// for it: the page is answered all the while from what the last growth published, and
// sees the growth in progress (its cells and time, frame by frame). A newer request (a
// saved file, a moved slider) cancels the growth at hand and grows again; stop() cancels
// it and grows nothing. Cancelling is cooperative, through WorldLimits::cancel.
//
// A text with errors may be a save caught half-written (an editor truncates the file, then
// writes it, or writes it in pieces): its errors are shown only once the files it read
// held still for a moment after the read, and a file that changed meanwhile is read again,
// so a save never flashes errors of a text the user did not write.
//
// A growth that fails or is stopped keeps the last model that grew: the page shows the
// diagnostics over the old model, as an editor keeps the last good build while the text
// is broken. Growth stays within interactive limits far below the command line's, which
// the page shows and can raise (setLimits).

#include <atomic>
#include <condition_variable>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "studio/interactive_limits.h"
#include "studio/program_options.h"

namespace ontogen::studio {

/// Cells a studio's growth may make unless raised on the page: a tree of a million
/// cells draws in a few seconds; a runaway rule reaches it in a few more steps, well
/// before the command line's 100 M (about 5 GB) would stop it.
inline constexpr uint64_t kStudioMaxCells = 1'000'000;
/// Bytes a studio's growth may hold unless raised on the page: 1 GiB, a tenth of a
/// small machine, while the browser and the editor hold the rest.
inline constexpr uint64_t kStudioMaxMemoryBytes = uint64_t{1} << 30;

struct StudioModelDef {
  /// The file, seed, threads, define values to start from; its limits are the ceiling
  /// setLimits may raise the interactive ones to.
  StudioProgramOptions program;
  std::optional<double> until;   ///< empty: the program's #until
  std::optional<int> frames;     ///< empty: the program's #fps, else kDefaultFrames
  /// The interpretation sets (`--interpret`); empty: the program's #interpret, else
  /// geometry. The music set's notes sound in the page.
  std::vector<std::string> sets;
  std::filesystem::path work;    ///< a folder of the studio's own for the outputs
  uint64_t maxCells = kStudioMaxCells;              ///< interactive limit, at most program.limits'
  uint64_t maxMemoryBytes = kStudioMaxMemoryBytes;  ///< interactive limit, at most program.limits'
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
  /// The page's value (a slider, or --define) is in effect, not the file's: the page
  /// says so until it is written into the file (writeDefine) or dropped (dropDefine).
  bool overridden = false;
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
  /// Stops the growth at hand and the model's thread.
  ~StudioModel();
  StudioModel(const StudioModel&) = delete;
  StudioModel& operator=(const StudioModel&) = delete;

  // Every member below may be called from any thread.

  /// Starts the model's growth thread; requests grow on it from then on.
  void start();
  /// Asks for a growth: cancels the one at hand, if any, and grows again on the model's
  /// thread (which start() must have started).
  void requestGrowth();
  /// Asks for a growth when the program file, a file it imports or a #surface file it
  /// names changed since the last growth read it; true when one did.
  bool refresh();
  /// Cancels the growth at hand and any asked for; the last model stays.
  void stop();
  /// Waits until no growth is asked for or running (or the timeout passes); true when so.
  bool waitIdle(std::chrono::milliseconds timeout = std::chrono::minutes(10)) const;
  /// Reads, compiles and grows now, on the calling thread (one growth at a time).
  void regrow();

  /// Gives a define a value for the growths to come (call requestGrowth() to see it).
  /// Throws std::invalid_argument, with nothing changed, when the program has no such
  /// define or the value is outside the range its slider spans (its #range).
  void setDefine(const std::string& name, double value);
  /// Writes the value a slider gave a define into the program file, in place of the number
  /// each `#define NAME` writes (the rest of the file byte for byte as it was), so the file
  /// says what the page shows; the page's value is then the file's. Returns the file's
  /// path. Throws std::invalid_argument, with nothing written, when the define has no value
  /// of the page's, the file is another tool's (converted when read), or the file changed
  /// since the last growth read it (a newer text the page has not seen).
  std::string writeDefine(const std::string& name);
  /// Drops the value a slider gave a define: the file's is in effect again (call
  /// requestGrowth() to see it). Throws std::invalid_argument when the define has none.
  void dropDefine(const std::string& name);
  /// Sets the interactive limits for the growths to come. Throws std::invalid_argument
  /// when one is 0 or above the ceiling the studio was started with.
  void setLimits(uint64_t maxCells, uint64_t maxMemoryBytes);
  /// The interactive limits and their ceiling. A growth's limit messages name the page's
  /// control, not the command line's flag (InteractiveLimits::worded).
  InteractiveLimits limits() const;

  /// Counts every growth that ended, failed or not.
  uint64_t version() const;
  /// Counts growths that gave a model: the version of glb().
  uint64_t modelVersion() const;
  /// The last model that grew, as the command line writes it; empty before one did.
  std::string glb() const;
  /// The image set's picture of frame `frame` of the last model that grew (PNG bytes, one
  /// a frame, as `ontogen run` writes them); empty when there is no such picture.
  std::string picture(std::size_t frame) const;
  /// The program text read at the last growth (converted, for another tool's file).
  std::string text() const;
  /// The file's name without folder and extension: names the outputs.
  std::string stem() const;
  /// The values in effect for the defines the text writes. A slider's value stays in effect
  /// over the file's until the file's own number for that define changes: an edit of the
  /// define in the file drops it (the file is the source of truth).
  std::map<std::string, double> defineValues() const;
  std::vector<StudioDefine> defines() const;
  std::vector<StudioNote> notes() const;
  const StudioModelDef& def() const { return def_; }
  /// The files besides the program file the last growth read and refresh() watches: its
  /// imports (at any depth), then its #surface files.
  std::vector<std::string> watchedFiles() const;

  /// What the page shows: versions, the model's frames (their developmental times, which
  /// Step goes through) and how many of them the image set pictured ("pictures"),
  /// diagnostics (each with the "file" it belongs to), defines, times, the "source" (the
  /// file as written: another tool's file before its conversion, its diagnostics at its
  /// own lines) and "sourceName" (the name its own diagnostics give as their file), the limits
  /// and the growth in progress ("growth": running, cells, time, seconds).
  nlohmann::json state() const;
  /// Counts changes of state(): each growth's start, frame and end, each setting.
  uint64_t changes() const;
  /// Waits until changes() differs from seen (or the timeout passes); returns changes().
  uint64_t waitForChange(uint64_t seen, std::chrono::milliseconds timeout) const;

 private:
  struct Diagnostic {
    std::string severity;
    int line = 0, column = 0;
    std::string message, formatted;
    std::string file;  // the source it belongs to, as diagnostics name it; empty: none
  };
  struct FileStamp {
    std::filesystem::file_time_type time{};
    uintmax_t size = 0;
    bool operator==(const FileStamp&) const = default;
  };
  // What one growth gives; published as a whole when it ends.
  struct Grown;
  static std::optional<FileStamp> stampOf(const std::string& path);
  // After a growth that failed: whether the files it read held still for kSettleTime.
  enum class Settling { Settled, Changed, Superseded };
  Settling settle();
  static constexpr std::chrono::milliseconds kSettleTime{200};
  static constexpr int kMaxRereads = 20;  // a file rewritten without end shows its errors
  void work();
  void growOnce();
  void grow(Grown& grown, const std::map<std::string, double>& overrides, const WorldLimits& limits);
  void changed();  // with mutex_ held
  std::vector<StudioDefine> definesInEffect() const;  // with mutex_ held: the sliders' values in

  StudioModelDef def_;
  std::atomic<bool> cancel_{false};
  std::mutex growing_;  // one growth at a time

  mutable std::mutex mutex_;  // everything below
  mutable std::condition_variable wake_;  // the model's thread: a growth asked for, or the end
  mutable std::condition_variable changedSignal_;
  std::thread thread_;
  bool started_ = false, quit_ = false, pending_ = false, running_ = false;
  uint64_t changes_ = 0;
  std::map<std::string, double> overrides_;  // from the sliders and --define
  uint64_t maxCells_, maxMemoryBytes_;
  // The stamp of each file the last growth read (the program file's, its imports', its
  // surfaces') as it was when that growth began or, for a file it read first, ended.
  std::map<std::string, std::optional<FileStamp>> stamps_;
  std::vector<std::string> watched_;  // the files besides the program file in stamps_
  std::string text_;
  std::string sourceName_;  // names the program's own diagnostics: the file's path, converted or not
  std::string shown_;       // the text the page shows: the file's own, before any conversion
  bool converted_ = false;  // text_ is converted from another tool's file
  std::string stem_;
  std::vector<StudioDefine> defines_;
  std::vector<Diagnostic> diagnostics_;
  std::vector<StudioNote> notes_;
  std::shared_ptr<const std::string> glb_;
  uint64_t version_ = 0;
  uint64_t modelVersion_ = 0;
  double from_ = 0, until_ = 0;
  std::vector<double> frames_;
  std::shared_ptr<const std::vector<std::string>> pictures_;  // the image set's, a frame each
  uint64_t cells_ = 0;
  double wallSeconds_ = 0;
  bool stopped_ = false;  // the last growth was cancelled
  // The growth in progress.
  std::chrono::steady_clock::time_point began_{};
  uint64_t growingCells_ = 0;
  double growingTime_ = 0;
};

}  // namespace ontogen::studio
