#pragma once
// A whole file's bytes, for what the studio serves (the model's .glb, the gallery's
// pictures) after a run wrote it.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ontogen::studio {

/// The bytes of the file at path; empty when it cannot be read.
inline std::string readFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace ontogen::studio
