#include "floornav/sensing/near_point_memory.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace floornav {

namespace {
// Twice the capacity, a power of two: probes stay short.
constexpr std::size_t kTableSize = std::bit_ceil(2 * NearPointMemory::kCapacity);
}  // namespace

NearPointMemory::NearPointMemory(double add, double keep, double cell)
    : add_(add),
      keep_(keep),
      inv_cell_(1.0 / cell),
      slot_index_(kTableSize, 0),
      slot_stamp_(kTableSize, 0) {
  points_.reserve(kCapacity);
  keys_.reserve(kCapacity);
}

void NearPointMemory::clear() {
  points_.clear();
  keys_.clear();
  refill_table();
}

std::uint64_t NearPointMemory::key_of(const Vec2& p) const {
  const auto ix = static_cast<std::int64_t>(std::floor(p.x() * inv_cell_));
  const auto iy = static_cast<std::int64_t>(std::floor(p.y() * inv_cell_));
  return (static_cast<std::uint64_t>(ix) << 32) ^ (static_cast<std::uint64_t>(iy) & 0xffffffffU);
}

std::size_t NearPointMemory::slot_of(std::uint64_t key) const {
  // Fibonacci hashing, then linear probing.
  std::size_t s = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >>
                                           (64 - std::countr_zero(kTableSize)));
  while (slot_stamp_[s] == stamp_ && keys_[slot_index_[s] - 1] != key)
    s = (s + 1) & (kTableSize - 1);
  return s;
}

void NearPointMemory::refill_table() {
  if (++stamp_ == 0) {  // the stamps wrapped: every slot must read empty again
    std::fill(slot_stamp_.begin(), slot_stamp_.end(), 0U);
    stamp_ = 1;
  }
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    const std::size_t s = slot_of(keys_[k]);
    slot_stamp_[s] = stamp_;
    slot_index_[s] = static_cast<std::uint32_t>(k + 1);
  }
}

std::span<const Vec2> NearPointMemory::update(std::span<const Vec2> points, const Vec2& centre,
                                              std::span<const Circle> moving) {
  const double keep_sq = keep_ * keep_, add_sq = add_ * add_;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < points_.size(); ++k) {
    if ((points_[k] - centre).squaredNorm() > keep_sq) continue;
    points_[kept] = points_[k];
    keys_[kept] = keys_[k];
    ++kept;
  }
  if (kept < points_.size()) {  // indices moved: the table is filed afresh
    points_.resize(kept);
    keys_.resize(kept);
    refill_table();
  }
  for (const Vec2& q : points) {
    if (points_.size() == kCapacity) break;
    // Not near, or not a number (a NaN compares false): not kept.
    if (!((q - centre).squaredNorm() <= add_sq)) continue;
    bool on_body = false;
    for (const Circle& c : moving)
      on_body = on_body || (q - c.center).squaredNorm() <= c.radius * c.radius;
    if (on_body) continue;
    const std::uint64_t key = key_of(q);
    const std::size_t s = slot_of(key);
    if (slot_stamp_[s] == stamp_) continue;  // that square holds a return already
    points_.push_back(q);
    keys_.push_back(key);
    slot_stamp_[s] = stamp_;
    slot_index_[s] = static_cast<std::uint32_t>(points_.size());
  }
  return points_;
}

}  // namespace floornav
