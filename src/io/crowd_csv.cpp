#include "floornav/io/crowd_csv.hpp"

#include <fmt/format.h>

#include "csv_field.hpp"

namespace floornav {

std::string crowd_to_csv(const CrowdResult& crowd) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "t,kind,name,x,y,theta\n");
  auto rows = [&](const std::vector<CrowdTrack>& tracks, const char* kind) {
    for (const CrowdTrack& t : tracks) {
      const std::string name = io_detail::csv_field(t.name);  // a comma or newline in it stays in
      for (const CrowdSample& s : t.samples)
        fmt::format_to(std::back_inserter(out), "{},{},{},{},{},{}\n", s.t, kind, name, s.x, s.y,
                       s.theta);
    }
  };
  rows(crowd.people, "person");
  rows(crowd.forklifts, "forklift");
  return fmt::to_string(out);
}

}  // namespace floornav
