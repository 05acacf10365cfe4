#include "floornav/io/crowd_csv.hpp"

#include <fmt/format.h>

namespace floornav {

std::string crowd_to_csv(const CrowdResult& crowd) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "t,kind,name,x,y,theta\n");
  auto rows = [&](const std::vector<CrowdTrack>& tracks, const char* kind) {
    for (const CrowdTrack& t : tracks)
      for (const CrowdSample& s : t.samples)
        fmt::format_to(std::back_inserter(out), "{},{},{},{},{},{}\n", s.t, kind, t.name, s.x, s.y,
                       s.theta);
  };
  rows(crowd.people, "person");
  rows(crowd.forklifts, "forklift");
  return fmt::to_string(out);
}

}  // namespace floornav
