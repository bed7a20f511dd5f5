#pragma once
// Temporary files a signal must not leave behind. An output is written to a temporary
// beside its target and renamed over it (output_file.h); a run stopped by SIGINT or
// SIGTERM in between would leave the temporary (`.NAME.tmpPID_N`, hundreds of MB for a
// large .glb). Each temporary is registered while it exists; once the handlers are
// installed, those signals unlink every registered file and then end the process as the
// signal would have. A folder of temporaries (the frames an .mp4 is encoded from) is
// registered as a folder: the signal removes the files in it, then the folder. The
// handler is async-signal-safe: it reads a fixed table of lock-free slots and calls only
// unlink, open, getdents64, unlinkat, rmdir, close, sigaction and raise.

#include <filesystem>

namespace ontogen {

/// Registers a temporary file for as long as it lives (from creation to rename or
/// removal). Past kMaxRegisteredTemporaries at once, later ones are not registered.
class RegisteredTemporary {
 public:
  RegisteredTemporary() = default;
  /// What a registered path is.
  enum class Kind {
    File,    ///< a file, unlinked
    Folder,  ///< a folder of files (no subfolders): its files are unlinked, then it
  };
  /// Registers `path`; register before the file is made, so that no signal falls between.
  explicit RegisteredTemporary(const std::filesystem::path& path, Kind kind = Kind::File) { hold(path, kind); }
  ~RegisteredTemporary() { release(); }
  /// Registers `path` in place of what was registered.
  void hold(const std::filesystem::path& path, Kind kind = Kind::File);
  /// Something is registered.
  bool held() const { return slot_ >= 0; }
  /// Registers nothing any more (the file was renamed, removed, or never made).
  void release();
  RegisteredTemporary(const RegisteredTemporary&) = delete;
  RegisteredTemporary& operator=(const RegisteredTemporary&) = delete;

 private:
  int slot_ = -1;
};

/// Temporaries registered at once: a run writes its outputs one at a time, so a few
/// writers on their own threads are the most there are.
inline constexpr int kMaxRegisteredTemporaries = 64;

/// Installs the SIGINT and SIGTERM handlers that remove the registered temporaries, for
/// the signals whose disposition is still the default (an ignored signal stays ignored).
/// For executables; a library never installs handlers itself. Idempotent.
void removeTemporariesOnSignals();

}  // namespace ontogen
