#pragma once
// Reading a program's text, or an imported file's, from disk. Only a regular file is
// read, and only up to a size limit: a device (/dev/zero, /dev/urandom) never ends, a
// FIFO blocks until someone writes, and a huge file would take memory a program never
// needs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace ontogen {

/// The most source text one program may have, the program file and every file it
/// imports together, bytes: 16 MiB. The models are a few KiB; checking costs about a
/// hundred bytes of memory per byte of source, so this keeps a check under 2 GB.
inline constexpr uint64_t kDefaultMaxSourceBytes = uint64_t{16} << 20;

struct SourceText {
  std::optional<std::string> text;  ///< empty when the file could not be read
  std::string error;                ///< why not, as in "it is a directory"
};

/// Reads the whole of `path` if it is a regular file of at most `maxBytes` bytes.
SourceText readSourceFile(const std::filesystem::path& path, uint64_t maxBytes);

/// "16 MiB", "1.5 KiB", "200 bytes": a size as messages print it.
std::string describeBytes(uint64_t bytes);

}  // namespace ontogen
