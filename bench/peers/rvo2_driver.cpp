// Times RVO2 (github.com/snape/RVO2, optimal reciprocal collision avoidance) on its own two
// examples, scaled to a given number of agents, for the peer comparison (bench/peers/README.md).
// Built against RVO2's library by bench/peers/build_rvo2.sh; not part of floornav's build.
//
//   rvo2_driver circle|blocks AGENTS STEPS [REPEATS]
//
// circle: examples/Circle.cc (agents on a circle heading to the antipodal point; time step
// 0.25 s, neighbour distance 15, 10 neighbours, horizons 10/10, radius 1.5, speed 2), the circle
// grown with the agent count so that neighbours start as far apart as in the example's 250
// (5 m of arc each). blocks: examples/Blocks.cc (four blocks of agents crossing past four square
// obstacles to the opposite corner; horizons 5/5, radius 2), each block of AGENTS/4 agents on the
// example's 10 m lattice, 10 columns wide. Both set the preferred velocities each step exactly as
// the examples do (blocks: with the example's small random perturbation, seeded with 1) and
// write nothing while timed. A run is STEPS steps of the whole crowd, or fewer when every agent
// has reached its goal (the examples' own test); a run is repeated REPEATS times (default 1),
// each from a new simulator, and the setup is not timed. Output: one line per run,
//   rvo2 <scenario> agents=<n> threads=<omp threads> steps=<s> seconds=<t> agent_steps_per_s=<r>
// Threads: RVO2's doStep is an OpenMP loop; set OMP_NUM_THREADS (build with OpenMP).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <RVO/RVO.h>

namespace {

const float kTwoPi = 6.28318530717958647692F;

void setup_circle(RVO::RVOSimulator& sim, std::vector<RVO::Vector2>& goals, std::size_t n) {
  sim.setTimeStep(0.25F);
  sim.setAgentDefaults(15.0F, 10U, 10.0F, 10.0F, 1.5F, 2.0F);
  const float radius = 200.0F * static_cast<float>(n) / 250.0F;
  for (std::size_t i = 0; i < n; ++i) {
    const float a = static_cast<float>(i) * kTwoPi / static_cast<float>(n);
    sim.addAgent(radius * RVO::Vector2(std::cos(a), std::sin(a)));
    goals.push_back(-sim.getAgentPosition(i));
  }
}

void setup_blocks(RVO::RVOSimulator& sim, std::vector<RVO::Vector2>& goals, std::size_t n) {
  sim.setTimeStep(0.25F);
  sim.setAgentDefaults(15.0F, 10U, 5.0F, 5.0F, 2.0F, 2.0F);
  const std::size_t per_block = n / 4, columns = 10;
  for (std::size_t k = 0; k < per_block; ++k) {
    const float i = static_cast<float>(k % columns), j = static_cast<float>(k / columns);
    sim.addAgent(RVO::Vector2(55.0F + i * 10.0F, 55.0F + j * 10.0F));
    goals.push_back(RVO::Vector2(-75.0F, -75.0F));
    sim.addAgent(RVO::Vector2(-55.0F - i * 10.0F, 55.0F + j * 10.0F));
    goals.push_back(RVO::Vector2(75.0F, -75.0F));
    sim.addAgent(RVO::Vector2(55.0F + i * 10.0F, -55.0F - j * 10.0F));
    goals.push_back(RVO::Vector2(-75.0F, 75.0F));
    sim.addAgent(RVO::Vector2(-55.0F - i * 10.0F, -55.0F - j * 10.0F));
    goals.push_back(RVO::Vector2(75.0F, 75.0F));
  }
  const float o[4][4][2] = {{{-10, 40}, {-40, 40}, {-40, 10}, {-10, 10}},
                            {{10, 40}, {10, 10}, {40, 10}, {40, 40}},
                            {{10, -40}, {40, -40}, {40, -10}, {10, -10}},
                            {{-10, -40}, {-10, -10}, {-40, -10}, {-40, -40}}};
  for (const auto& poly : o) {
    std::vector<RVO::Vector2> v;
    for (const auto& p : poly) v.push_back(RVO::Vector2(p[0], p[1]));
    sim.addObstacle(v);
  }
  sim.processObstacles();
}

// The examples' setPreferredVelocities (Blocks adds the perturbation against deadlocks).
void set_preferred(RVO::RVOSimulator& sim, const std::vector<RVO::Vector2>& goals, bool perturb) {
  for (std::size_t i = 0; i < sim.getNumAgents(); ++i) {
    RVO::Vector2 g = goals[i] - sim.getAgentPosition(i);
    if (RVO::absSq(g) > 1.0F) g = RVO::normalize(g);
    sim.setAgentPrefVelocity(i, g);
    if (perturb) {
      const float angle = static_cast<float>(std::rand()) * kTwoPi / static_cast<float>(RAND_MAX);
      const float dist = static_cast<float>(std::rand()) * 0.0001F / static_cast<float>(RAND_MAX);
      sim.setAgentPrefVelocity(
          i, sim.getAgentPrefVelocity(i) + dist * RVO::Vector2(std::cos(angle), std::sin(angle)));
    }
  }
}

// The examples' reachedGoal: within one radius (circle) or 20 m (blocks) of every goal.
bool reached(const RVO::RVOSimulator& sim, const std::vector<RVO::Vector2>& goals, bool blocks) {
  for (std::size_t i = 0; i < sim.getNumAgents(); ++i) {
    const float r = blocks ? 20.0F : sim.getAgentRadius(i);
    if (RVO::absSq(sim.getAgentPosition(i) - goals[i]) > r * r) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || (std::strcmp(argv[1], "circle") != 0 && std::strcmp(argv[1], "blocks") != 0)) {
    std::fprintf(stderr, "usage: rvo2_driver circle|blocks AGENTS STEPS [REPEATS]\n");
    return 2;
  }
  const bool blocks = std::strcmp(argv[1], "blocks") == 0;
  const std::size_t n = std::strtoul(argv[2], nullptr, 10);
  const long steps = std::strtol(argv[3], nullptr, 10);
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 1;
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  for (int r = 0; r < repeats; ++r) {
    std::srand(1);
    RVO::RVOSimulator sim;
    std::vector<RVO::Vector2> goals;
    if (blocks)
      setup_blocks(sim, goals, n);
    else
      setup_circle(sim, goals, n);
    const auto t0 = std::chrono::steady_clock::now();
    long done = 0;
    while (done < steps && !reached(sim, goals, blocks)) {
      set_preferred(sim, goals, blocks);
      sim.doStep();
      ++done;
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("rvo2 %s agents=%zu threads=%d steps=%ld seconds=%.6f agent_steps_per_s=%.0f\n",
                argv[1], sim.getNumAgents(), threads, done, s,
                static_cast<double>(done) * static_cast<double>(sim.getNumAgents()) / s);
  }
  return 0;
}
