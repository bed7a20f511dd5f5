#include "lang/source_reader.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace ontogen {

namespace fs = std::filesystem;

std::string describeBytes(uint64_t bytes) {
  char text[64];
  if (bytes >= (uint64_t{1} << 20) && bytes % (uint64_t{1} << 20) == 0)
    std::snprintf(text, sizeof text, "%llu MiB", static_cast<unsigned long long>(bytes >> 20));
  else if (bytes >= (uint64_t{1} << 20))
    std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1 << 20));
  else if (bytes >= 1024)
    std::snprintf(text, sizeof text, "%.1f KiB", static_cast<double>(bytes) / 1024);
  else
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  return text;
}

SourceText readSourceFile(const fs::path& path, uint64_t maxBytes) {
  // The kind is asked before the file is opened: opening a FIFO would block.
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error) return {std::nullopt, error.message()};
  if (fs::is_directory(status)) return {std::nullopt, "it is a folder, not a file"};
  if (!fs::is_regular_file(status))
    return {std::nullopt, "it is not a regular file (a device, a FIFO or a socket); a program is read from a file"};
  const uint64_t size = fs::file_size(path, error);
  const std::string tooLarge = "it is larger than the limit of " + describeBytes(maxBytes) + " of source text";
  if (!error && size > maxBytes) return {std::nullopt, tooLarge + " (" + describeBytes(size) + ")"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return {std::nullopt, std::strerror(errno)};
  // Read at most one byte past the limit: a file may grow, or report no size (/proc).
  std::string text;
  text.resize(static_cast<size_t>(std::min<uint64_t>(size, maxBytes)) + 1);
  size_t have = 0;
  while (in && have < text.size()) {
    in.read(text.data() + have, static_cast<std::streamsize>(text.size() - have));
    have += static_cast<size_t>(in.gcount());
    if (have == text.size() && have <= maxBytes) text.resize(std::min<uint64_t>(maxBytes, 2 * have) + 1);
  }
  if (in.bad()) return {std::nullopt, std::strerror(errno)};
  if (have > maxBytes) return {std::nullopt, tooLarge};
  text.resize(have);
  return {std::move(text), ""};
}

}  // namespace ontogen
