#include "floornav/render/trajectory_html.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include "floornav/render/palette.hpp"
#include "floornav/render/replay_assets.hpp"
#include "floornav/scenario/ranges_interval.hpp"
#include "replay_data.hpp"
#include "run_caption.hpp"

namespace floornav {

namespace {

using namespace render_detail;

/// `text` with every `<` written as `\u003c`: JSON that cannot end its <script> element early.
std::string script_safe_json(const nlohmann::ordered_json& data) {
  const std::string json = data.dump();
  std::string out;
  out.reserve(json.size() + 64);
  for (char c : json) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

/// `text` escaped for HTML content.
std::string html_text(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// The template with each `{{name}}` replaced once by its value, in one pass.
std::string fill_template(
    std::string_view tpl,
    const std::vector<std::pair<std::string_view, std::string_view>>& values) {
  std::size_t size = tpl.size();
  for (const auto& [k, v] : values) size += v.size();
  std::string out;
  out.reserve(size);
  std::size_t at = 0;
  while (at < tpl.size()) {
    const std::size_t open = tpl.find("{{", at);
    if (open == std::string_view::npos) break;
    const std::size_t close = tpl.find("}}", open + 2);
    if (close == std::string_view::npos) break;
    const std::string_view key = tpl.substr(open + 2, close - open - 2);
    const auto it =
        std::find_if(values.begin(), values.end(), [&](const auto& kv) { return kv.first == key; });
    out.append(tpl.substr(at, open - at));
    if (it != values.end())
      out.append(it->second);
    else
      out.append(tpl.substr(open, close + 2 - open));  // not ours: left as it was
    at = close + 2;
  }
  out.append(tpl.substr(std::min(at, tpl.size())));
  return out;
}

std::string render_page(const Scenario& scenario, std::span<const Track> tracks,
                        const Caption& caption, std::string_view status, double duration,
                        const CrowdResult* crowd = nullptr) {
  const std::string data = script_safe_json(replay_data(scenario.world.get(), tracks, scenario.sim,
                                                        replay_ranges_interval(scenario), caption,
                                                        status, duration, crowd));
  const std::string title = html_text(caption.title);
  return fill_template(kReplayTemplate, {{"title", title},
                                         {"style", kReplayStyle},
                                         {"data", data},
                                         {"core", kReplayCore},
                                         {"app", kReplayApp}});
}

double duration_of(std::span<const Track> tracks) {
  double d = 0.0;
  for (const Track& t : tracks)
    if (!t.run->trajectory.empty()) d = std::max(d, t.run->trajectory.back().t);
  return d;
}

}  // namespace

int replay_ranges_interval(const Scenario& s) {
  return ranges_interval_within(s, static_cast<double>(kMaxReplayRangeValues));
}

std::string render_trajectory_html(const Scenario& s, const RunResult& r) {
  const Track track{&s.robot(), &r, ""};
  const std::span<const Track> tracks(&track, 1);
  return render_page(s, tracks, run_caption(s, r), to_string(r.status), duration_of(tracks));
}

std::string render_fleet_html(const Scenario& s, const FleetResult& f) {
  std::vector<Track> tracks;
  for (std::size_t i = 0; i < f.robots.size() && i < s.robots.size(); ++i)
    tracks.push_back({&s.robots[i], &f.robots[i], robot_color(i)});
  if (tracks.size() == 1) tracks.front().color.clear();
  return render_page(s, tracks, fleet_caption(s, f), to_string(f.status), duration_of(tracks),
                     &f.crowd);
}

}  // namespace floornav
