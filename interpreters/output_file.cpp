#include "interpreters/output_file.h"

#include "interpreters/temporary_files.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace ontogen {

namespace {

// Tries this many names before giving up: collisions need another writer racing for the
// same target, so a handful of names is plenty.
constexpr int kNameAttempts = 100;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int error) {
  std::string message = "cannot write '" + path.string() + "': " + what;
  if (error != 0) message += std::string(what.empty() ? "" : ": ") + std::strerror(error);
  throw OutputError(message);
}

/// Creates a new, empty file beside path with a name no one else uses, with the
/// permissions a new file gets (0666 less the umask), and returns its path. The name is
/// registered before the file is made (temporary_files.h), so a signal removes it.
std::filesystem::path createTemporary(const std::filesystem::path& path, RegisteredTemporary& registered) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path directory = path.parent_path();
  for (int attempt = 0; attempt < kNameAttempts; ++attempt) {
    std::string name = "." + path.filename().string() + ".tmp" + std::to_string(::getpid()) +
                       "_" + std::to_string(counter++);
    std::filesystem::path temporary = directory / name;
    registered.hold(temporary);
    int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return temporary;
    }
    registered.release();
    if (errno != EEXIST) fail(path, "", errno);
  }
  fail(path, "no free temporary name", EEXIST);
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write) {
  if (path.filename().empty()) fail(path, "not a file name", 0);
  // Registered until it is renamed or removed, so that SIGINT and SIGTERM remove it too.
  RegisteredTemporary registered;
  const std::filesystem::path temporary = createTemporary(path, registered);
  auto discard = [&] {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  };
  try {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail(path, "cannot open the temporary file", errno);
    errno = 0;  // so that a failure below reports the error of the failing write
    write(out);
    out.flush();
    if (!out) fail(path, "write error", errno);
    out.close();
    if (!out) fail(path, "write error on close", errno);
  } catch (...) {
    discard();
    throw;
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    discard();
    throw OutputError("cannot write '" + path.string() + "': " + error.message());
  }
}

}  // namespace ontogen
