#pragma once
// A barrier for the fleet's threads that spins before it sleeps. Internal to the library.
//
// Why not std::barrier: libstdc++'s spins a few dozen times and then sleeps in the kernel, and a
// thread woken from there through the hypervisor of a virtual machine comes back tens of
// microseconds later, twice per fleet step. OpenMP's barriers spin for a while first (libgomp's
// GOMP_SPINCOUNT); so does this one, then it waits on the atomic as std::barrier does.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace floornav::sim_detail {

// About a millisecond of spinning.
inline constexpr int kBarrierSpins = 1 << 15;

inline void spin_pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// Spins until ready() or the budget `spins` (at most `max_spins`) is spent; true when ready()
// held. The budget adapts: a wait that has to sleep halves it, one that ends while spinning
// doubles it back. When other processes hold the cores, the thread awaited is often off its
// core: spinning would keep it off longer (a fleet of 100 on two busy cores stepped 10 times
// slower).
template <class Ready>
bool spin_until(std::atomic<int>& spins, int max_spins, const Ready& ready) {
  const int budget = spins.load(std::memory_order_relaxed);
  for (int i = 0; i < budget; ++i) {
    if (ready()) {
      if (budget < max_spins)
        spins.store(std::min(max_spins, 2 * budget + 1), std::memory_order_relaxed);
      return true;
    }
    spin_pause();
  }
  // Never below a few microseconds: a budget of 0 could not grow back.
  spins.store(std::max(budget / 2, std::min(max_spins, 64)), std::memory_order_relaxed);
  return false;
}

template <class Completion>
class SpinBarrier {
 public:
  // `spins`: at most how long a waiting thread spins before it sleeps (0 when there are more
  // threads than cores, where a spinning thread would hold up another).
  SpinBarrier(std::size_t threads, Completion completion, int spins = kBarrierSpins)
      : threads_(threads), max_spins_(spins), spins_(spins), completion_(completion) {}

  // Blocks until `threads` calls have arrived; the last to arrive runs the completion first.
  // Everything written before arriving is visible to every thread after it returns.
  void arrive_and_wait() {
    const std::uint32_t generation = generation_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads_) {
      completion_();
      arrived_.store(0, std::memory_order_relaxed);
      generation_.store(generation + 1, std::memory_order_release);
      generation_.notify_all();
      return;
    }
    // A fleet phase of 1,000 robots on two threads is a few hundred microseconds.
    if (spin_until(spins_, max_spins_,
                   [&] { return generation_.load(std::memory_order_acquire) != generation; }))
      return;
    while (generation_.load(std::memory_order_acquire) == generation)
      generation_.wait(generation, std::memory_order_acquire);
  }

 private:
  const std::size_t threads_;
  const int max_spins_;
  std::atomic<int> spins_;  ///< the spinning budget now
  Completion completion_;
  std::atomic<std::size_t> arrived_{0};
  std::atomic<std::uint32_t> generation_{0};
};

}  // namespace floornav::sim_detail
