#include "interpreters/music/score_output.h"

#include <stdexcept>
#include <string>

#include "interpreters/output_file.h"

namespace ontogen {

std::vector<std::filesystem::path> ScoreOutput::write(const Score& score, const FrameTarget& target) {
  std::vector<std::filesystem::path> written;
  if (def_.writeFile) {
    std::string name = target.stem.empty() ? std::string("music") : target.stem;
    if (target.frameCount > 1) {
      std::string number = std::to_string(target.frame);
      if (number.size() < 4) number.insert(0, 4 - number.size(), '0');
      name += "_" + number;
    }
    std::filesystem::path path = target.directory / (name + ".mid");
    MidiFileDef file = def_.file;
    file.name = target.stem;
    // Encode first: a score that cannot be encoded leaves no file behind.
    std::vector<uint8_t> bytes;
    try {
      bytes = encodeMidiFile(score, file);
    } catch (const std::invalid_argument& error) {
      throw OutputError(path.string() + ": " + error.what());
    }
    writeFileAtomically(path, [&](std::ostream& out) {
      out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    });
    written.push_back(std::move(path));
  }
  if (performer_) performer_(score, def_.file);
  return written;
}

}  // namespace ontogen
