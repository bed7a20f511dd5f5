#include "core/limits.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <fstream>
#include <string>

#include "model/message_number.h"

namespace ontogen {

namespace {
std::string mebibytes(uint64_t bytes) { return std::to_string(bytes >> 20); }

// The memory of the machine, 0 when it does not say.
uint64_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long pageSize = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return 0;
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(pageSize);
}

uint64_t addressSpaceBytes() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  return static_cast<uint64_t>(limit.rlim_cur);
}

// At or past this a cgroup v1 limit means none: "unlimited" is the largest page count,
// 2^63 - 4096 with 4 KiB pages (less with larger pages), and no machine has 2^62 bytes.
constexpr uint64_t kUnlimitedV1 = uint64_t{1} << 62;

// Whether the comma-separated `list` names `name`.
bool lists(const std::string& list, const std::string& name) {
  for (size_t at = 0; at <= list.size();) {
    size_t end = list.find(',', at);
    if (end == std::string::npos) end = list.size();
    if (list.compare(at, end - at, name) == 0) return true;
    at = end + 1;
  }
  return false;
}

// The group of `controller` in `root`/proc/self/cgroup ("0::/a/b" for v2, whose
// controllers field is empty; "4:memory:/a/b" or "4:cpu,memory:/a/b" for v1), empty when
// the process is in none.
std::string groupOf(const std::string& root, const std::string& controller) {
  std::ifstream in(root + "/proc/self/cgroup");
  for (std::string line; std::getline(in, line);) {
    const size_t first = line.find(':');
    const size_t second = first == std::string::npos ? first : line.find(':', first + 1);
    if (second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const bool match = controller.empty() ? controllers.empty() && line.compare(0, first, "0") == 0
                                          : lists(controllers, controller);
    if (match) return line.substr(second + 1);
  }
  return "";
}

// The least limit in `file` of the group `group` and its ancestors under `mount`, read
// by `parse` (0: none). A container often mounts its own group as the root of the
// hierarchy, where the group's path from /proc/self/cgroup does not exist: the mount's
// own file is read too.
template <class Parse>
uint64_t leastLimit(const std::string& mount, std::string group, const std::string& file, Parse parse) {
  uint64_t least = 0;
  auto take = [&](const std::string& path) {
    std::ifstream in(path);
    std::string text;
    if (!(in >> text)) return;
    const uint64_t bytes = parse(text);
    if (bytes > 0 && (least == 0 || bytes < least)) least = bytes;
  };
  while (!group.empty() && group != "/") {
    take(mount + group + "/" + file);
    const size_t slash = group.rfind('/');
    group = slash == std::string::npos ? "" : group.substr(0, slash);
  }
  take(mount + "/" + file);
  return least;
}

// A whole number of bytes, 0 for anything else ("max", "-1", junk, past 2^64).
uint64_t parseBytes(const std::string& text) {
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::stoull(text);
}
}  // namespace

uint64_t readControlGroupV2Bytes(const std::string& root) {
  return leastLimit(root + "/sys/fs/cgroup", groupOf(root, ""), "memory.max", parseBytes);
}

uint64_t readControlGroupV1Bytes(const std::string& root) {
  return leastLimit(root + "/sys/fs/cgroup/memory", groupOf(root, "memory"), "memory.limit_in_bytes",
                    [](const std::string& text) {
                      const uint64_t bytes = parseBytes(text);
                      return bytes >= kUnlimitedV1 ? 0 : bytes;
                    });
}

MemoryBounds readMemoryBounds(const std::string& root) {
  return {physicalMemoryBytes(), readControlGroupV2Bytes(root), readControlGroupV1Bytes(root), addressSpaceBytes()};
}

uint64_t memoryAvailableBytes(const MemoryBounds& bounds) {
  uint64_t least = 0;
  for (const uint64_t bytes : {bounds.physical, bounds.controlGroupV2, bounds.controlGroupV1, bounds.addressSpace})
    if (bytes > 0 && (least == 0 || bytes < least)) least = bytes;
  return least;
}

uint64_t defaultMemoryLimitBytes(const MemoryBounds& bounds) {
  const uint64_t memory = memoryAvailableBytes(bounds);
  return memory == 0 ? uint64_t{8} << 30 : std::max<uint64_t>(memory / 2, uint64_t{1} << 20);
}

uint64_t defaultMemoryLimitBytes() {
  static const uint64_t limit = defaultMemoryLimitBytes(readMemoryBounds());
  return limit;
}

void checkCellLimit(uint64_t cells, const WorldLimits& limits) {
  if (cells > limits.maxCells) [[unlikely]]
    throw LimitError("the model grew past " + std::to_string(limits.maxCells) +
                     " cells, the cell limit; raise it with --max-cells N");
}

void checkTotalCellLimit(uint64_t cells, const WorldLimits& limits) {
  if (cells > limits.maxCells) [[unlikely]]
    throw LimitError("the model grew past " + std::to_string(limits.maxCells) +
                     " cells in all its systems, the cell limit; raise it with --max-cells N");
}

void checkSeedCellLimit(uint64_t cells, const WorldLimits& limits) {
  if (cells > limits.maxCells) [[unlikely]]
    throw LimitError("the pool starts with " + std::to_string(cells) + " cells, past the cell limit of " +
                     std::to_string(limits.maxCells) + "; raise it with --max-cells N");
}

void checkMemoryLimit(uint64_t bytes, const WorldLimits& limits) {
  if (bytes > limits.maxMemoryBytes) [[unlikely]]
    throw LimitError("the model's pools passed " + mebibytes(limits.maxMemoryBytes) +
                     " MiB, the memory limit; raise it with --max-memory MIB");
}

void checkOutsideMemory(const std::string& what, uint64_t bytes, uint64_t held, const WorldLimits& limits) {
  if (bytes > limits.maxMemoryBytes || held > limits.maxMemoryBytes - bytes) [[unlikely]]
    throw LimitError(what + " needs about " + std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB" +
                     ((held >> 20) > 0 ? " besides the " + mebibytes(held) + " MiB held" : "") +
                     ", past the memory limit of " + mebibytes(limits.maxMemoryBytes) +
                     " MiB; raise it with --max-memory MIB");
}

void checkGridMemory(uint64_t sites, uint64_t bytesPerSite, const WorldLimits& limits, uint64_t held) {
  const uint64_t limit = limits.maxMemoryBytes;
  // Compared by division so that no product overflows.
  if (held > limit || sites > (limit - held) / bytesPerSite) [[unlikely]]
    throw LimitError("the grid's " + std::to_string(sites) + " sites need more than the memory limit of " +
                     mebibytes(limit) + " MiB; raise it with --max-memory MIB");
}

void checkEventLimit(uint64_t events, double when, const WorldLimits& limits) {
  if (events > limits.maxEventsPerStep) [[unlikely]]
    throw LimitError("more than " + std::to_string(limits.maxEventsPerStep) +
                     " terminal-age events in one step (near t = " + messageNumber(when) +
                     "); a lifetime much shorter than the step? Use a smaller --step, or raise --max-events N");
}

void checkStepLimit(uint64_t steps, double more, double dt, double target, const WorldLimits& limits) {
  // `more` may be huge or infinite (a denormal step): compare as doubles.
  const double total = static_cast<double>(steps) + more;
  if (!(total <= static_cast<double>(limits.maxSteps))) [[unlikely]]
    throw LimitError("reaching t = " + messageNumber(target) + " in steps of " + messageNumber(dt) + " s takes " +
                     (std::isfinite(total) ? messageNumber(total) : "more than " + messageNumber(DBL_MAX)) +
                     " steps, past the step limit of " +
                     std::to_string(limits.maxSteps) + "; use a larger --step, or raise it with --max-steps N");
}

void checkTimeAdvances(double time, double next, double dt) {
  if (!(next > time)) [[unlikely]]
    throw LimitError("a step of " + messageNumber(dt) + " s no longer moves the time on at t = " + messageNumber(time) +
                     " (it is below the precision of the time there); use a larger --step");
}

}  // namespace ontogen
