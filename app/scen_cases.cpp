#include "scen_cases.hpp"

#include "floornav/io/input_error.hpp"

namespace floornav {

std::vector<BatchCase> make_scen_cases(const std::string&, const std::string& scen_file, double,
                                       std::span<const std::string>) {
  throw InputError(scen_file, "", "MovingAI batches are being wired in");
}

}  // namespace floornav
