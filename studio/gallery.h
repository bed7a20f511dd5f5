#pragma once
// Interactive evolution (papers 000 and 004): a gallery of variants of the studio's
// program, bred from the ones the user picks. The variants and their operators are the
// library's (lang/variation.h): each variant is the program's text with its `#define`
// values (and, if asked, numeric constants) mutated, seeded, so a gallery is the same for
// the same file, seed and picks. Each variant is grown to its end and pictured as the
// command line pictures it (`--format png`).
//
// Breeding keeps the picked variants (elitism) and fills the rest of the next generation
// with children: uniform crossover of two picked parents, in turn, then a mutation.
//
// Making a generation (reset, breed) only decides its variants' programs, which is quick;
// growing and picturing them is separate, one variant at a time (growNext), so that the
// studio grows them off the request's thread (studio/gallery_grower.h) and the page shows
// each picture as it comes. growAll() grows them all at once.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lang/variation.h"
#include "studio/program_options.h"

namespace ontogen::studio {

struct GalleryDef {
  StudioProgramOptions program;  ///< seed, limits, threads of each variant's world
  std::optional<double> until;   ///< empty: each variant's #until
  int size = 12;                 ///< variants a generation
  uint64_t seed = 1;             ///< of the mutations
  bool constants = false;        ///< vary numeric constants as well as defines
  int thumbnailSide = 240;       ///< pixels
  std::filesystem::path work;    ///< a folder of the gallery's own
  std::filesystem::path saveTo;  ///< where saved variants go
};

struct GalleryVariant {
  Genome genome;
  std::string text;          ///< the variant's program
  bool grown = false;        ///< it was grown and pictured (or failed): png or error holds the outcome
  std::string png;           ///< its picture; empty when it failed or is not grown yet
  std::string error;         ///< why it failed (the first diagnostic), empty when it grew
  std::vector<int> parents;  ///< indices in the previous generation; empty in the first
};

/// A variant still to grow: what growing it needs, taken from the gallery so that it can
/// grow while the gallery is read (and made anew) elsewhere.
struct GalleryTask {
  uint64_t epoch = 0;  ///< of the generation it belongs to (Gallery::epoch())
  int index = 0;
  std::string text;
  std::string stem;  ///< of the studio's file, which names the variant's program in its messages
};

/// What growing a variant gave: its picture, or why it has none.
struct GalleryPicture {
  std::string png;
  std::string error;
};

class Gallery {
 public:
  explicit Gallery(GalleryDef def);

  /// Starts again from a program text: generation 1, mutations of the text's own values,
  /// none grown yet. Throws std::invalid_argument when the text does not lex.
  void reset(const std::string& text, const std::string& stem);
  /// The next generation from the picked variants (indices into variants()), none grown
  /// yet; a variant need not be grown to be picked. Throws std::invalid_argument when none
  /// is picked or an index is out of range.
  void breed(const std::vector<int>& picked);

  /// The first variant of this generation not grown yet; none when all are.
  std::optional<GalleryTask> nextTask() const;
  /// Grows a task's variant and pictures it, as `--format png` would. Reads only the
  /// gallery's settings, never its variants, so it may run while they change; `cancel`
  /// (may be null) stops the growth from another thread, which then gives an error.
  GalleryPicture grow(const GalleryTask& task, const std::atomic<bool>* cancel = nullptr) const;
  /// Keeps what grow() gave; ignored when the task's generation has been replaced since.
  void keep(const GalleryTask& task, GalleryPicture picture);
  /// Grows every variant of this generation not grown yet, one after the other.
  void growAll();
  /// Counts a generation anew at each reset and breed: what tells a task of a replaced
  /// generation from one of this.
  uint64_t epoch() const { return epoch_; }
  /// Variants of this generation grown so far.
  int grown() const;
  /// Writes a variant's program beside the others saved, named by generation and index
  /// (`STEM_gG_vK.cell` in GalleryDef::saveTo, the stem stripped of separators and "..");
  /// returns its path. Throws std::invalid_argument on a bad index, OutputError when it
  /// cannot be written.
  std::filesystem::path save(int index) const;

  int generation() const { return generation_; }
  const std::vector<GalleryVariant>& variants() const { return variants_; }
  bool ready() const { return space_ != nullptr; }
  const VariationSpace& space() const { return *space_; }
  /// Generation, genes, variants (without pictures: /gallery/N.png serves them), how far
  /// the generation's growth is ("grown" variants of the "variants", "growing" while some
  /// are not), and a "warning" when the program has nothing to vary (empty otherwise).
  nlohmann::json state() const;

 private:
  uint64_t seedOf(int index, uint64_t salt) const;
  void startGeneration();

  GalleryDef def_;
  std::unique_ptr<VariationSpace> space_;
  std::string stem_;
  int generation_ = 0;
  uint64_t epoch_ = 0;
  std::vector<GalleryVariant> variants_;
};

}  // namespace ontogen::studio
