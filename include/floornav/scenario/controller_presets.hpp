#pragma once
/// @file
/// Named controller configurations (`controller.preset`), applied before the section's own keys:
///   - `factory`: the product's best navigation for real floors, as shipped in the templates and
///     the fleet and crowd scenes: the A* planner stack over the chapter's automaton on the known
///     floor plan, the safety layer and reciprocal avoidance (ORCA);
///   - `chapter`: the chapter's automaton alone, as the textbook has it: no planner, no safety
///     layer, no reciprocal avoidance (the chapter-alone rows of docs/BENCHMARKS.md).
/// Without a preset a controller section is the chapter's automaton with the safety layer and
/// reciprocal avoidance (the defaults of ControllerConfig).

#include <span>
#include <string_view>

#include "floornav/nav/controller.hpp"

namespace floornav {

/// Sets `config` to the preset called `name`; false when there is none of that name.
bool apply_controller_preset(std::string_view name, ControllerConfig& config);
std::span<const std::string_view> controller_preset_names();

}  // namespace floornav
