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
// Variants must differ visibly, so the first generation varies only the defines that
// change the picture. reset() first grows probes: the program as written, then each
// `#define` at the low end of its range and, if that pictured the same, at the high end
// (each with the other defines as written). A define whose probes all picture what the
// program as written does (a define of the music alone, one that is never used, a scale
// that each picture frames whole) is held at its value: no variant changes it, and the
// state lists it as "held". A probe that fails where the program grows differs from it.
// Numeric constants (GalleryDef::constants) are asked for by name and always varied.
//
// Making a generation (breed) only decides its variants' programs, which is quick;
// growing and picturing them is separate, one probe or variant at a time (nextTask, grow,
// keep), so that the studio grows them off the request's thread
// (studio/gallery_grower.h) and the page shows each picture as it comes. The first
// generation's variants are decided once the probes are in. growAll() grows them all.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lang/variation.h"
#include "studio/interactive_limits.h"
#include "studio/program_options.h"

namespace ontogen::studio {

struct GalleryDef {
  /// Seed, threads of each variant's world; its limits are the ceiling of the interactive
  /// ones the variants grow within (Gallery::setLimits), which start at them.
  StudioProgramOptions program;
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

/// A variant or probe still to grow: what growing it needs, taken from the gallery so
/// that it can grow while the gallery is read (and made anew) elsewhere.
struct GalleryTask {
  uint64_t epoch = 0;  ///< of the generation it belongs to (Gallery::epoch())
  int index = 0;       ///< of the variant, or of the probe when `probe`
  bool probe = false;  ///< a probe of what changes the picture (see above), not a variant
  std::string text;
  std::string stem;  ///< of the studio's file, which names the variant's program in its messages
  /// The limits it grows within; none given (0 cells): the GalleryDef's.
  InteractiveLimits limits = {};
};

/// What growing a variant gave: its picture, or why it has none.
struct GalleryPicture {
  std::string png;
  std::string error;
};

class Gallery {
 public:
  explicit Gallery(GalleryDef def);

  /// Starts again from a program text: generation 1, whose variants (mutations of the
  /// text's own values) are decided once the probes have grown (probing()). Throws
  /// std::invalid_argument when the text does not lex.
  void reset(const std::string& text, const std::string& stem);
  /// The next generation from the picked variants (indices into variants()), none grown
  /// yet; a variant need not be grown to be picked. Throws std::invalid_argument when none
  /// is picked, an index is out of range or the probes are still growing.
  void breed(const std::vector<int>& picked);

  /// The next probe to grow while probing, else the first variant of this generation
  /// not grown yet; none when all are.
  std::optional<GalleryTask> nextTask() const;
  /// Grows a task's probe or variant and pictures it, as `--format png` would. Reads only the
  /// gallery's settings, never its variants, so it may run while they change; `cancel`
  /// (may be null) stops the growth from another thread, which then gives an error.
  GalleryPicture grow(const GalleryTask& task, const std::atomic<bool>* cancel = nullptr) const;
  /// Keeps what grow() gave; ignored when the task's generation has been replaced since.
  /// The last probe's decides the first generation's variants.
  void keep(const GalleryTask& task, GalleryPicture picture);
  /// Grows every probe and variant of this generation not grown yet, one after the other.
  void growAll();
  /// The interactive limits the probes and variants to come grow within, as the page sets
  /// them for the model; a variant past one says so by the page's control.
  void setLimits(const InteractiveLimits& limits) { limits_ = limits; }
  /// The probes of reset() are still growing: the first generation has no variants yet.
  bool probing() const { return probing_; }
  /// The defines held at their value because no probe of theirs changed the picture.
  const std::vector<std::string>& held() const { return held_; }
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
  /// Generation, genes (the varied ones), the defines "held", variants (without
  /// pictures: /gallery/N.png serves them), how far the generation's growth is ("grown"
  /// variants of the "variants", "growing" while some are not; "probing" with "probed"
  /// of at most "probes" while the probes grow), and a "warning" when nothing would vary
  /// (empty otherwise).
  nlohmann::json state() const;

 private:
  /// The program with one define gene (of all the text's) at one end of its range; gene
  /// -1: the program as written.
  struct Probe {
    int gene = -1;
    double value = 0;
    bool grown = false;
    GalleryPicture picture;
  };
  uint64_t seedOf(int index, uint64_t salt) const;
  bool probeNeeded(std::size_t index) const;
  bool changesThePicture(const Probe& probe) const;
  void decideFirstGeneration();
  void writeVariantTexts();

  GalleryDef def_;
  InteractiveLimits limits_;
  std::unique_ptr<VariationSpace> space_;  // the genes varied (all, while probing)
  std::string text_;                       // as reset() was given it
  std::string stem_;
  bool probing_ = false;
  std::vector<Probe> probes_;
  std::vector<std::string> held_;
  int generation_ = 0;
  uint64_t epoch_ = 0;
  std::vector<GalleryVariant> variants_;
};

}  // namespace ontogen::studio
