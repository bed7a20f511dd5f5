#include "interpreters/temporary_files.h"

#include <atomic>
#include <csignal>
#include <cstring>

#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace ontogen {

namespace {

// A slot is free, being filled (the handler skips it) or holds a path to remove.
enum SlotState : int { kFree = 0, kFilling = 1, kHeld = 2 };

constexpr std::size_t kMaxPath = 4096;

struct Slot {
  std::atomic<int> state{kFree};
  bool folder = false;  // written before the state becomes kHeld
  char path[kMaxPath] = {};
};

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slots");

Slot slots[kMaxRegisteredTemporaries];

// The files in `path`, then the folder, with system calls only: opendir and readdir may
// allocate, so the entries are read with getdents64 into a buffer on the stack.
void removeFolder(const char* path) {
  const int folder = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder < 0) return;
  alignas(8) char buffer[4096];
  for (;;) {
    const long bytes = ::syscall(SYS_getdents64, folder, buffer, sizeof buffer);
    if (bytes <= 0) break;
    for (long at = 0; at < bytes;) {
      // struct linux_dirent64: inode (8 bytes), offset (8), record length (2), type (1), name.
      unsigned short length = 0;
      std::memcpy(&length, buffer + at + 16, sizeof length);
      const char* name = buffer + at + 19;
      const bool dot = name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'));
      if (!dot) ::unlinkat(folder, name, 0);
      at += length;
    }
  }
  ::close(folder);
  ::rmdir(path);
}

extern "C" void removeTemporariesAndRaise(int signal) {
  for (Slot& slot : slots) {
    if (slot.state.load(std::memory_order_acquire) != kHeld) continue;
    if (slot.folder)
      removeFolder(slot.path);
    else
      ::unlink(slot.path);
  }
  // Back to the default action (even if the handler was put back without SA_RESETHAND, as
  // live playback does), which ends the process once the handler returns and the signal,
  // raised again, is delivered.
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  ::sigaction(signal, &fallback, nullptr);
  ::raise(signal);
}

void install(int signal) {
  struct sigaction current {};
  if (::sigaction(signal, nullptr, &current) != 0 || current.sa_handler != SIG_DFL) return;
  struct sigaction action {};
  action.sa_handler = removeTemporariesAndRaise;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  ::sigaction(signal, &action, nullptr);
}

}  // namespace

void RegisteredTemporary::hold(const std::filesystem::path& path, Kind kind) {
  release();
  const std::string& text = path.native();
  if (text.size() >= kMaxPath) return;
  for (int i = 0; i < kMaxRegisteredTemporaries; ++i) {
    int expected = kFree;
    if (!slots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acq_rel)) continue;
    std::memcpy(slots[i].path, text.c_str(), text.size() + 1);
    slots[i].folder = kind == Kind::Folder;
    slots[i].state.store(kHeld, std::memory_order_release);
    slot_ = i;
    return;
  }
}

void RegisteredTemporary::release() {
  if (slot_ >= 0) slots[slot_].state.store(kFree, std::memory_order_release);
  slot_ = -1;
}

void removeTemporariesOnSignals() {
  static const bool installed = [] {
    install(SIGINT);
    install(SIGTERM);
    return true;
  }();
  (void)installed;
}

}  // namespace ontogen
