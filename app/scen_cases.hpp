#pragma once
// Turns a MovingAI .scen file and a template scenario into batch cases.

#include <span>
#include <string>
#include <vector>

#include "floornav/io/batch.hpp"

namespace floornav {

std::vector<BatchCase> make_scen_cases(const std::string& template_file,
                                       const std::string& scen_file, double cell_size,
                                       std::span<const std::string> overrides);

}  // namespace floornav
