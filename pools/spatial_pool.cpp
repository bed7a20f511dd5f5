#include "pools/spatial_pool.h"

#include <algorithm>
#include <cmath>

namespace ontogen {

namespace {
constexpr int64_t kBucketLimit = (int64_t{1} << 20) - 1;  // 21 bits per axis in a key
}

SpatialPool::SpatialPool(double radius, std::vector<std::array<int, 3>> positionSlots)
    : radius_(radius), slots_(std::move(positionSlots)) {}

std::array<double, 3> SpatialPool::positionOf(size_t i) const {
  const CellRecord& cell = cells_[i];
  std::array<double, 3> p{0, 0, 0};
  if (cell.master >= slots_.size()) return p;
  const auto& slots = slots_[cell.master];
  for (int axis = 0; axis < 3; ++axis)
    if (slots[axis] >= 0) p[axis] = state_[cell.state + slots[axis]];
  return p;
}

std::array<int64_t, 3> SpatialPool::bucketOf(const std::array<double, 3>& p) const {
  std::array<int64_t, 3> b{0, 0, 0};
  for (int axis = 0; axis < 3; ++axis) {
    // Far-away or non-finite positions share the edge buckets: distances are still
    // checked exactly, so only the speed suffers.
    const double q = std::isfinite(p[axis]) ? std::floor(p[axis] / radius_) : 0.0;
    b[axis] = static_cast<int64_t>(std::clamp(q, -double(kBucketLimit), double(kBucketLimit)));
  }
  return b;
}

uint64_t SpatialPool::bucketKey(int64_t x, int64_t y, int64_t z) {
  auto part = [](int64_t v) { return static_cast<uint64_t>(v + kBucketLimit + 1) & 0x1FFFFF; };
  return part(x) | (part(y) << 21) | (part(z) << 42);
}

int64_t SpatialPool::denseIndex(int64_t x, int64_t y, int64_t z) const {
  x -= low_[0];
  y -= low_[1];
  z -= low_[2];
  if (x < 0 || y < 0 || z < 0 || x >= extent_[0] || y >= extent_[1] || z >= extent_[2]) return -1;
  return x + extent_[0] * (y + extent_[1] * z);
}

void SpatialPool::index() {
  const size_t n = cells_.size();
  std::vector<std::array<int64_t, 3>> bucket(n);
  std::array<int64_t, 3> high{0, 0, 0};
  low_ = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    bucket[i] = bucketOf(positionOf(i));
    for (int axis = 0; axis < 3; ++axis) {
      low_[axis] = i == 0 ? bucket[i][axis] : std::min(low_[axis], bucket[i][axis]);
      high[axis] = i == 0 ? bucket[i][axis] : std::max(high[axis], bucket[i][axis]);
    }
  }
  for (int axis = 0; axis < 3; ++axis) extent_[axis] = high[axis] - low_[axis] + 1;
  const double boxes = static_cast<double>(extent_[0]) * static_cast<double>(extent_[1]) * static_cast<double>(extent_[2]);
  dense_ = boxes <= 4.0 * static_cast<double>(n) + 64;
  order_.resize(n);
  buckets_.clear();
  start_.clear();
  if (dense_) {
    // Counting sort by bucket: stable, so pool order within a bucket.
    start_.assign(static_cast<size_t>(boxes) + 1, 0);
    std::vector<uint32_t> slot(n);
    for (size_t i = 0; i < n; ++i) {
      slot[i] = static_cast<uint32_t>(denseIndex(bucket[i][0], bucket[i][1], bucket[i][2]));
      ++start_[slot[i] + 1];
    }
    for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
    std::vector<uint32_t> next(start_.begin(), start_.end() - 1);
    for (uint32_t i = 0; i < n; ++i) order_[next[slot[i]]++] = i;
  } else {
    std::vector<std::pair<uint64_t, uint32_t>> keyed(n);
    for (uint32_t i = 0; i < n; ++i) keyed[i] = {bucketKey(bucket[i][0], bucket[i][1], bucket[i][2]), i};
    std::sort(keyed.begin(), keyed.end());
    for (uint32_t k = 0; k < n; ++k) order_[k] = keyed[k].second;
    buckets_.reserve(n);
    for (uint32_t k = 0; k < n;) {
      uint32_t end = k;
      while (end < n && keyed[end].first == keyed[k].first) ++end;
      buckets_.emplace(keyed[k].first, std::make_pair(k, end));
      k = end;
    }
  }
  sorted_.resize(n);
  for (size_t k = 0; k < n; ++k) sorted_[k] = positionOf(order_[k]);
  ++version_;
}

size_t SpatialPool::indexBytes() const {
  // A hashed bucket is a node of the table (its key, range and link, about 40 bytes with
  // the allocator's header) and a slot of its bucket array.
  constexpr size_t kHashedBucketBytes = 40 + sizeof(void*);
  return order_.capacity() * sizeof(uint32_t) + sorted_.capacity() * sizeof(sorted_[0]) +
         start_.capacity() * sizeof(uint32_t) + buckets_.size() * kHashedBucketBytes +
         buckets_.bucket_count() * sizeof(void*) + flat_.capacity() * sizeof(uint32_t) +
         starts_.capacity() * sizeof(uint32_t);
}

template <typename Found>
void SpatialPool::scanAround(const std::array<double, 3>& p, size_t self, Found&& found) const {
  const auto b = bucketOf(p);
  const double r2 = radius_ * radius_;
  auto scan = [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      const auto& q = sorted_[k];
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
      if (d2 <= r2 && order_[k] != self) found(k);
    }
  };
  for (int64_t dz = -1; dz <= 1; ++dz)
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dx = -1; dx <= 1; ++dx) {
        if (dense_) {
          const int64_t at = denseIndex(b[0] + dx, b[1] + dy, b[2] + dz);
          if (at >= 0) scan(start_[at], start_[at + 1]);
          continue;
        }
        auto it = buckets_.find(bucketKey(b[0] + dx, b[1] + dy, b[2] + dz));
        if (it != buckets_.end()) scan(it->second.first, it->second.second);
      }
}

void SpatialPool::neighbours(size_t i, std::vector<uint32_t>& out) const {
  out.clear();
  scanAround(positionOf(i), i, [&](uint32_t k) { out.push_back(order_[k]); });
}

void SpatialPool::neighbourTable(LargeVector<uint32_t>& offsets, LargeVector<uint32_t>& cells) const {
  const size_t n = order_.size();
  // The queries in bucket order (their positions are sorted_, contiguous), each list
  // appended in that order...
  flat_.clear();
  starts_.resize(n + 1);
  for (size_t k = 0; k < n; ++k) {
    starts_[k] = static_cast<uint32_t>(flat_.size());
    scanAround(sorted_[k], order_[k], [&](uint32_t found) { flat_.push_back(order_[found]); });
  }
  starts_[n] = static_cast<uint32_t>(flat_.size());
  // ...then the rows moved to pool order, a contiguous copy each.
  offsets.assign(n + 1, 0);
  for (size_t k = 0; k < n; ++k) offsets[order_[k] + 1] = starts_[k + 1] - starts_[k];
  for (size_t i = 0; i < n; ++i) offsets[i + 1] += offsets[i];
  cells.resize(flat_.size());
  for (size_t k = 0; k < n; ++k)
    std::copy(flat_.begin() + starts_[k], flat_.begin() + starts_[k + 1], cells.begin() + offsets[order_[k]]);
}

}  // namespace ontogen
