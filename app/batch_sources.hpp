#pragma once
// Where a batch's cases come from: scenario files, the rows of a MovingAI .scen file, a folder of
// Gazebo worlds (BARN), a grid of parameter values over a template, or generated floors. A source
// holds no case: each is made when it is needed, so that neither a .scen of a million rows nor a
// grid of 100 values over a 4-Mcell map holds more than the cases being run, and --limit and
// --shard make only what they select. A source's sweep id fingerprints every input of every case
// (the template, the --set and --grid values, the files each case reads: maps, their images,
// people files, worlds), whatever --limit and --shard select.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "floornav/runner/batch.hpp"
#include "sweep_id.hpp"

namespace floornav {

/// `count` cases, numbered 0..count-1; `make(id)` makes one (and throws InputError for a bad
/// one). `checked`: every case was made, and so checked, when the source was made (a few files, a
/// .scen's rows); otherwise the caller checks the cases it selects before running any.
struct CaseSource {
  std::size_t count{0};
  std::function<BatchCase(std::size_t id)> make;
  bool checked{false};
};

/// One case per scenario file, each with the --set values `overrides`.
CaseSource make_file_cases(std::span<const std::string> files,
                           std::span<const std::string> overrides, SweepHasher& hash);

/// One case per row of a MovingAI .scen file, on its map (found beside it), with the template's
/// robot and controller; `cell_size` metres per cell.
CaseSource make_scen_cases(const std::string& template_file, const std::string& scen_file,
                           double cell_size, std::span<const std::string> overrides,
                           SweepHasher& hash);

/// One case per .world/.sdf file in `dir` (in natural order: world_2 before world_10), with the
/// template's robot, controller, start and goal. With `barn_paths`, each world_N also gets the
/// BARN optimal time from path_N.npy.
CaseSource make_world_cases(const std::string& template_file, const std::string& dir,
                            const std::string& barn_paths, std::span<const std::string> overrides,
                            SweepHasher& hash);

/// One case per combination of the `grid` values ("key=FROM:TO:COUNT", COUNT evenly spaced values
/// from FROM to TO, or "key=V1,V2,..."), the last key varying fastest, on the template with the
/// --set values `overrides` first. Each case's line carries its values (`swept`).
CaseSource make_grid_cases(const std::string& template_file, std::span<const std::string> grid,
                           std::span<const std::string> overrides, SweepHasher& hash);

/// `count` generated factory floors (bench_cases.hpp: a walled 20 x 20 m hall of 50 random
/// star-shaped obstacles, floor seed `first_seed + i`), each with a tour of four goals across
/// it drawn from that seed; robot, controller and sim from the template (its world, start and
/// goals are replaced).
CaseSource make_floor_cases(const std::string& template_file, int count, std::uint64_t first_seed,
                            std::span<const std::string> overrides, SweepHasher& hash);

/// `count` generated shared floors (scenario/shared_floor.hpp: a hall with pillars and boxes, 4 to
/// 12 robots on routes of 1 to 3 goals, people and a forklift on some; floor seed
/// `first_seed + i`), every robot the template's robot and controller, sim from the template.
CaseSource make_shared_floor_cases(const std::string& template_file, int count,
                                   std::uint64_t first_seed, std::span<const std::string> overrides,
                                   SweepHasher& hash);

}  // namespace floornav
