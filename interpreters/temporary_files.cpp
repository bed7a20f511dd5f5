#include "interpreters/temporary_files.h"

#include <atomic>
#include <csignal>
#include <cstring>

#include <unistd.h>

namespace ontogen {

namespace {

// A slot is free, being filled (the handler skips it) or holds a path to remove.
enum SlotState : int { kFree = 0, kFilling = 1, kHeld = 2 };

constexpr std::size_t kMaxPath = 4096;

struct Slot {
  std::atomic<int> state{kFree};
  char path[kMaxPath] = {};
};

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slots");

Slot slots[kMaxRegisteredTemporaries];

extern "C" void removeTemporariesAndRaise(int signal) {
  for (Slot& slot : slots)
    if (slot.state.load(std::memory_order_acquire) == kHeld) ::unlink(slot.path);
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

void RegisteredTemporary::hold(const std::filesystem::path& path) {
  release();
  const std::string& text = path.native();
  if (text.size() >= kMaxPath) return;
  for (int i = 0; i < kMaxRegisteredTemporaries; ++i) {
    int expected = kFree;
    if (!slots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acq_rel)) continue;
    std::memcpy(slots[i].path, text.c_str(), text.size() + 1);
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
