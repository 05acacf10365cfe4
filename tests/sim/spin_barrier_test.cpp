#include "spin_barrier.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

namespace floornav::sim_detail {
namespace {

// Each phase, every thread writes its slot and arrives; the completion runs once per phase, on
// one thread, after every write of the phase and before any write of the next. Some phases
// keep one thread away for milliseconds, past the spinning, so the others sleep and are woken.
void run_phases(int threads, int spins) {
  const int kThreads = threads, kPhases = 2000;
  std::vector<long> slot(static_cast<std::size_t>(kThreads), 0);
  int completions = 0;
  bool consistent = true;
  auto completion = [&]() noexcept {
    ++completions;
    for (const long v : slot) consistent = consistent && v == completions;
  };
  SpinBarrier<decltype(completion)> barrier(static_cast<std::size_t>(kThreads), completion, spins);
  auto work = [&](int t) {
    for (int p = 0; p < kPhases; ++p) {
      slot[static_cast<std::size_t>(t)] = p + 1;
      if (t == p % kThreads && p % 500 == 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      barrier.arrive_and_wait();
    }
  };
  {
    std::vector<std::jthread> threads;
    for (int t = 1; t < kThreads; ++t) threads.emplace_back(work, t);
    work(0);
  }
  EXPECT_EQ(completions, kPhases);
  EXPECT_TRUE(consistent);
}

TEST(SpinBarrier, CompletionOncePerPhaseSeesEveryWriteAndSleepersWake) {
  run_phases(2, kBarrierSpins);
}

// More threads than cores: no spinning, every wait sleeps.
TEST(SpinBarrier, WithoutSpinningToo) {
  run_phases(3, 0);
}

}  // namespace
}  // namespace floornav::sim_detail
