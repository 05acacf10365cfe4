// Times Stage (github.com/rtv/Stage) headless: loads a world file, runs WARMUP updates, then times
// UPDATES calls of World::Update(), the call Stage's own headless loop (`stage -g`, World::Run)
// makes once per simulation step. Each update advances the world by its interval_sim (100 ms)
// and, for the worlds of bench/peers/make_worlds.py, takes one laser scan and one move per robot
// (the laser's and the position model's update intervals are 100 ms too). Built against libstage
// by bench/peers/build_stage.sh; not part of floornav's build (bench/peers/README.md).
//
//   stage_driver WORLD_FILE UPDATES [WARMUP] [ROBOTS]
//
// Output: one line, stage updates=<n> seconds=<t> updates_per_s=<u> robot_updates_per_s=<u *
// ROBOTS>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include <Stage-4.3/stage.hh>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: stage_driver WORLD_FILE UPDATES [WARMUP] [ROBOTS]\n");
    return 2;
  }
  const char* file = argv[1];
  const long updates = std::strtol(argv[2], nullptr, 10);
  const long warmup = argc > 3 ? std::strtol(argv[3], nullptr, 10) : 10;
  const long robots = argc > 4 ? std::strtol(argv[4], nullptr, 10) : 1;
  Stg::Init(&argc, &argv);
  // Never destroyed, as in Stage's own main (its model destructors crash at exit).
  Stg::World* world = new Stg::World(file);
  world->Load(file);
  for (long i = 0; i < warmup; ++i) world->Update();
  const auto t0 = std::chrono::steady_clock::now();
  for (long i = 0; i < updates; ++i) world->Update();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("stage updates=%ld seconds=%.6f updates_per_s=%.1f robot_updates_per_s=%.1f\n",
              updates, s, updates / s, updates * robots / s);
  std::fflush(stdout);
  std::_Exit(0);
}
