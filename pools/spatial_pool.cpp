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

void SpatialPool::index() {
  const size_t n = cells_.size();
  std::vector<uint64_t> keys(n);
  for (size_t i = 0; i < n; ++i) {
    auto b = bucketOf(positionOf(i));
    keys[i] = bucketKey(b[0], b[1], b[2]);
  }
  order_.resize(n);
  for (uint32_t i = 0; i < n; ++i) order_[i] = i;
  std::sort(order_.begin(), order_.end(),
            [&](uint32_t a, uint32_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  buckets_.clear();
  buckets_.reserve(n);
  for (uint32_t k = 0; k < n;) {
    uint32_t end = k;
    while (end < n && keys[order_[end]] == keys[order_[k]]) ++end;
    buckets_.emplace(keys[order_[k]], std::make_pair(k, end));
    k = end;
  }
  ++version_;
}

void SpatialPool::neighbours(size_t i, std::vector<uint32_t>& out) const {
  out.clear();
  const auto p = positionOf(i);
  const auto b = bucketOf(p);
  const double r2 = radius_ * radius_;
  for (int64_t dz = -1; dz <= 1; ++dz)
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dx = -1; dx <= 1; ++dx) {
        auto it = buckets_.find(bucketKey(b[0] + dx, b[1] + dy, b[2] + dz));
        if (it == buckets_.end()) continue;
        for (uint32_t k = it->second.first; k < it->second.second; ++k) {
          const uint32_t j = order_[k];
          if (j == i) continue;
          const auto q = positionOf(j);
          const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
          if (d2 <= r2) out.push_back(j);
        }
      }
}

}  // namespace ontogen
