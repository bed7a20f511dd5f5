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
  std::string png;           ///< its picture; empty when it failed
  std::string error;         ///< why it failed (the first diagnostic), empty when it grew
  std::vector<int> parents;  ///< indices in the previous generation; empty in the first
};

class Gallery {
 public:
  explicit Gallery(GalleryDef def);

  /// Starts again from a program text: generation 1, mutations of the text's own values.
  /// Throws std::invalid_argument when the text does not lex.
  void reset(const std::string& text, const std::string& stem);
  /// The next generation from the picked variants (indices into variants()); throws
  /// std::invalid_argument when none is picked or an index is out of range.
  void breed(const std::vector<int>& picked);
  /// Writes a variant's program beside the others saved, named by generation and index
  /// (`STEM_gG_vK.cell` in GalleryDef::saveTo, the stem stripped of separators and "..");
  /// returns its path. Throws std::invalid_argument on a bad index, OutputError when it
  /// cannot be written.
  std::filesystem::path save(int index) const;

  int generation() const { return generation_; }
  const std::vector<GalleryVariant>& variants() const { return variants_; }
  bool ready() const { return space_ != nullptr; }
  const VariationSpace& space() const { return *space_; }
  /// Generation, genes and variants (without pictures: /gallery/N.png serves them).
  nlohmann::json state() const;

 private:
  void render(GalleryVariant& variant, int index) const;
  uint64_t seedOf(int index, uint64_t salt) const;

  GalleryDef def_;
  std::unique_ptr<VariationSpace> space_;
  std::string stem_;
  int generation_ = 0;
  std::vector<GalleryVariant> variants_;
};

}  // namespace ontogen::studio
