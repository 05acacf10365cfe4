#pragma once
// The cases the speed measurements use besides the generated floors of
// floornav/scenario/factory_floor.hpp, so that `floornav bench` and the Google Benchmark binary
// (bench/) time exactly the same work.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>

#include "floornav/scenario/factory_floor.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// Where the AWS RoboMaker small-warehouse map (0.05 m cells) lies under a shared maps folder.
std::filesystem::path aws_warehouse_map(const std::filesystem::path& maps_dir);

/// The TurtleBot3 Burger preset (360-beam lidar) driving the length of the AWS warehouse's
/// west aisle, from (-5, -8.5) to (-5, 8.5). std::nullopt when the map file is missing.
std::optional<Scenario> make_aws_scenario(const std::filesystem::path& maps_dir);

}  // namespace floornav
