#pragma once
// The open list of the octile searches (best_first_search.hpp): a radix heap on f.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

// In an unnamed namespace, as best_first_search.hpp is (one copy per search's file).
namespace floornav {
namespace {

/// An open-list entry: lowest f first; among equal f the deepest node (-g lowest), then the
/// lowest index, so that the order of expansion (and the path) is deterministic.
struct OpenEntry {
  double f;
  double neg_g;
  std::uint32_t index;
  bool operator>(const OpenEntry& o) const {
    if (f != o.f) return f > o.f;
    if (neg_g != o.neg_g) return neg_g > o.neg_g;
    return index > o.index;
  }
};

/// The open list, a radix heap on f: A* with a consistent heuristic pops f in increasing order, so
/// an entry whose f differs from the last popped one first in bit b (of f's IEEE pattern, which
/// orders non-negative doubles as unsigned integers do) waits in bucket b + 1, unsorted, until
/// everything below it is gone. Bucket 0 holds the entries with f at most the last popped one,
/// sorted on (f, -g, index), the best last: pops come out in the order of one priority queue over
/// all entries (the order is total, so the path is that of any exact priority queue).
/// Bucket 0 is a sorted vector, not a heap, because of where its pushes land: an entry pushed while
/// cell u is expanded has f at most u's (else it goes to a higher bucket) and, at equal f, a
/// larger g (u's g plus a step), so it is better than u, which was the best of all: it goes on top,
/// or below the few entries pushed just before it from the same u. Only the odd entry a rounding
/// puts an ulp off scans further down. Pushes and pops are therefore O(1) where a binary heap of
/// the hundreds of entries that tie on f would sift through its levels, with the same paths
/// (BM_FloorOptimumAstar in bench/optimum_bench.cpp decides this).
class OpenList {
 public:
  void clear() {
    for (auto& b : buckets_) b.clear();
    last_ = 0;
    size_ = 0;
  }
  bool empty() const { return size_ == 0; }
  void push(const OpenEntry& e) {
    ++size_;
    const std::uint64_t key = bits(e.f);
    if (key <= last_) {
      push_ordered(e);
      return;
    }
    buckets_[bucket_of(key)].push_back(e);
  }
  OpenEntry pop() {
    --size_;
    auto& zero = buckets_[0];
    if (zero.empty()) {
      std::size_t b = 1;
      while (buckets_[b].empty()) ++b;
      auto& from = buckets_[b];
      std::uint64_t least = bits(from.front().f);
      for (const OpenEntry& e : from) least = std::min(least, bits(e.f));
      last_ = least;
      for (const OpenEntry& e : from) {
        const std::uint64_t key = bits(e.f);
        if (key == least)
          zero.push_back(e);
        else
          buckets_[bucket_of(key)].push_back(e);  // a lower bucket: they share the top bits
      }
      from.clear();
      std::sort(zero.begin(), zero.end(), std::greater<OpenEntry>{});  // the best last
    }
    const OpenEntry top = zero.back();
    zero.pop_back();
    return top;
  }

 private:
  static std::uint64_t bits(double f) { return std::bit_cast<std::uint64_t>(f); }
  std::size_t bucket_of(std::uint64_t key) const {
    return static_cast<std::size_t>(64 - std::countl_zero(key ^ last_));
  }
  void push_ordered(const OpenEntry& e) {
    // Insertion from the top: e is nearly always the best already.
    auto& zero = buckets_[0];
    std::size_t i = zero.size();
    zero.push_back(e);
    for (; i > 0 && e > zero[i - 1]; --i) zero[i] = zero[i - 1];
    zero[i] = e;
  }

  std::array<std::vector<OpenEntry>, 65> buckets_;
  std::uint64_t last_{0};
  std::size_t size_{0};
};

}  // namespace
}  // namespace floornav
