#include "floornav/io/run_mcap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "floornav/geometry/angle.hpp"
#include "floornav/io/cdr_writer.hpp"
#include "floornav/io/mcap_writer.hpp"
#include "floornav/io/provenance.hpp"
#include "floornav/io/ros2_definitions.hpp"
#include "floornav/io/ros2_messages.hpp"
#include "floornav/scenario/ranges_interval.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sim/goal_rows.hpp"
#include "world_raster.hpp"

namespace floornav {

namespace {

constexpr double kCrowdMarkerPeriod = 0.1;  ///< s between two /crowd messages
constexpr int kRingBins = 360;              ///< /ring_scan: one-degree bins round the robot
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr auto kSensorPeriodNs = static_cast<std::uint64_t>(kMcapSensorPeriod * 1e9);
constexpr std::uint64_t kPeriodSlack = 1000;  ///< ns: steps of dt add up to the period within this

std::uint64_t nanoseconds(double t) {
  return t > 0.0 ? static_cast<std::uint64_t>(std::llround(t * 1e9)) : 0;
}

/// A robot of the bag: its task, its run, and its names.
struct BagRobot {
  const RobotTask* task;
  const RunResult* run;
  std::string topic;  ///< "" for a lone robot, "/<name>" in a fleet
  std::string frame;  ///< "" for a lone robot, "<name>/" in a fleet
};

/// How a robot's sensors are published: lidars as scans, the rest as a ring scan or one range.
struct SensorGroup {
  enum Kind { Lidar, Ring, Single } kind;
  std::size_t begin{0}, end{0};      ///< lidar: sensors [begin, end)
  std::vector<std::size_t> members;  ///< ring and single: the sensors
  std::string topic, frame;
  Pose2 mount{};  ///< the frame in base_link
  Ros2ScanShape shape{};
  double max_range{0.0};  ///< lidar: every beam's (a reading at it saw nothing)
};

/// A lidar: a run of at least kLidarBeams single beams on one mount point with one range and one
/// turn from beam to beam (make_lidar's, or a preset's; across the +-pi seam too).
constexpr std::size_t kLidarBeams = 16;

std::vector<std::pair<std::size_t, std::size_t>> lidar_runs(std::span<const RangeSensorSpec> s) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  const auto beam = [&](std::size_t i) { return s[i].cone_angle == 0.0 || s[i].cone_rays == 1; };
  std::size_t i = 0;
  while (i < s.size()) {
    std::size_t j = i + 1;
    if (beam(i) && j < s.size()) {
      const double step = wrap_angle(s[j].mount.theta - s[i].mount.theta);
      while (j < s.size() && beam(j) && s[j].mount.position == s[i].mount.position &&
             s[j].min_range == s[i].min_range && s[j].max_range == s[i].max_range &&
             std::abs(wrap_angle(s[j].mount.theta - s[j - 1].mount.theta) - step) < 1e-9 &&
             std::abs(step) > 1e-9)
        ++j;
    }
    if (j - i >= kLidarBeams) {
      out.emplace_back(i, j);
      i = j;
    } else {
      ++i;
    }
  }
  return out;
}

std::vector<SensorGroup> sensor_groups(const RobotSpec& robot, const BagRobot& b, double dt) {
  std::vector<SensorGroup> out;
  std::vector<bool> in_lidar(robot.sensors.size(), false);
  int lidars = 0;
  for (const auto& [begin, end] : lidar_runs(robot.sensors)) {
    SensorGroup g{SensorGroup::Lidar, begin, end, {}, "", "", {}, {}};
    for (std::size_t i = begin; i < end; ++i) in_lidar[i] = true;
    const RangeSensorSpec& first = robot.sensors[begin];
    const std::string suffix = lidars == 0 ? "" : fmt::format("_{}", lidars);
    g.topic = b.topic + "/scan" + suffix;
    g.frame = b.frame + "lidar" + suffix;
    g.mount = {first.mount.position, 0.0};
    const double step = wrap_angle(robot.sensors[begin + 1].mount.theta - first.mount.theta);
    g.shape.angle_min = static_cast<float>(first.mount.theta);
    g.shape.angle_increment = static_cast<float>(step);
    g.shape.angle_max =
        static_cast<float>(first.mount.theta + step * static_cast<double>(end - begin - 1));
    g.shape.range_min = static_cast<float>(first.min_range);
    g.shape.range_max = static_cast<float>(first.max_range);
    g.shape.scan_time = static_cast<float>(dt);
    g.max_range = first.max_range;
    out.push_back(std::move(g));
    ++lidars;
  }
  std::vector<std::size_t> rest;
  for (std::size_t i = 0; i < robot.sensors.size(); ++i)
    if (!in_lidar[i]) rest.push_back(i);
  if (rest.size() == 1) {
    SensorGroup g{SensorGroup::Single,          0, 0, rest, b.topic + "/range", b.frame + "range",
                  robot.sensors[rest[0]].mount, {}};
    out.push_back(std::move(g));
  } else if (rest.size() > 1) {
    SensorGroup g{SensorGroup::Ring,     0,  0, rest, b.topic + "/ring_scan",
                  b.frame + "base_link", {}, {}};
    const double step = 2.0 * std::numbers::pi / kRingBins;
    g.shape.angle_min = static_cast<float>(-std::numbers::pi);
    g.shape.angle_increment = static_cast<float>(step);
    g.shape.angle_max = static_cast<float>(-std::numbers::pi + step * (kRingBins - 1));
    double reach = 0.0;
    for (std::size_t i : rest)
      reach = std::max(reach, robot.sensors[i].mount.position.norm() + robot.sensors[i].max_range);
    g.shape.range_max = static_cast<float>(reach);
    g.shape.scan_time = static_cast<float>(dt);
    out.push_back(std::move(g));
  }
  return out;
}

/// The shapes of the world as markers: the bounds and each polygon as a closed line, each circle
/// as a short cylinder.
std::vector<Ros2Marker> world_markers(const World& world) {
  std::vector<Ros2Marker> out;
  const std::array<float, 4> grey{0.45f, 0.45f, 0.5f, 1.0f};
  const auto outline = [&](std::string ns, int id, std::span<const Vec2> points) {
    Ros2Marker m;
    m.frame = "map";
    m.ns = std::move(ns);
    m.id = id;
    m.type = Ros2Marker::kLineStrip;
    m.scale = {0.02, 0.0, 0.0};  // line width
    m.color = grey;
    for (const Vec2& p : points) m.points.push_back({p.x(), p.y(), 0.0});
    if (!points.empty()) m.points.push_back({points.front().x(), points.front().y(), 0.0});
    out.push_back(std::move(m));
  };
  if (const auto& b = world.bounds()) {
    const Vec2 corners[] = {b->min, {b->max.x(), b->min.y()}, b->max, {b->min.x(), b->max.y()}};
    outline("bounds", 0, corners);
  }
  int id = 0;
  for (const auto& poly : world.polygons()) outline("polygons", id++, poly);
  id = 0;
  for (const Circle& c : world.circles()) {
    Ros2Marker m;
    m.frame = "map";
    m.ns = "circles";
    m.id = id++;
    m.type = Ros2Marker::kCylinder;
    m.x = c.center.x();
    m.y = c.center.y();
    m.z = 0.15;
    m.scale = {2.0 * c.radius, 2.0 * c.radius, 0.3};
    m.color = grey;
    out.push_back(std::move(m));
  }
  return out;
}

/// The channels of the bag, created on first use (with their schema).
class Channels {
 public:
  explicit Channels(McapWriter& mcap) : mcap_(mcap) {}
  std::uint16_t operator()(const std::string& topic, const std::string& type) {
    if (const auto it = channels_.find(topic); it != channels_.end()) return it->second;
    auto schema = schemas_.find(type);
    if (schema == schemas_.end())
      schema =
          schemas_.emplace(type, mcap_.add_schema(type, "ros2msg", ros2_message_definition(type)))
              .first;
    // The ros2 profile's channel metadata; "" (no recorded offer): `ros2 bag play` offers its
    // defaults (docs/OUTPUTS.md gives the overrides that latch /map and /tf_static).
    const std::uint16_t id =
        mcap_.add_channel(schema->second, topic, "cdr", {{"offered_qos_profiles", ""}});
    channels_.emplace(topic, id);
    return id;
  }

 private:
  McapWriter& mcap_;
  std::map<std::string, std::uint16_t> schemas_;
  std::map<std::string, std::uint16_t> channels_;
};

/// Everything of one robot that is published step by step.
struct RobotStream {
  const BagRobot* robot{nullptr};
  std::vector<SensorGroup> sensors;
  std::vector<std::int64_t> goal_rows;
  std::size_t next_goal{0};
  std::size_t next_transition{0};
  std::size_t next_frame{0};
  int last_mode{std::numeric_limits<int>::min()};
  bool scanned{false};         ///< a sensor frame was published
  std::uint64_t last_scan{0};  ///< ns, when
  std::uint16_t odom{0}, tf{0}, mode{0}, transition{0}, goal{0};
  std::vector<std::uint16_t> sensor_channels;
  std::string odom_frame, base_frame;
  std::optional<Ros2PoseMessages> pose;  ///< /odom and /tf, patched row by row
};

class BagWriter {
 public:
  BagWriter(const Scenario& s, std::vector<BagRobot> robots, const CrowdResult* crowd,
            const McapWriter::Sink& sink)
      : scenario_(s),
        robots_(std::move(robots)),
        crowd_(crowd),
        mcap_(sink, McapOptions{.library = "floornav " + floornav_version()}),
        channels_(mcap_) {}

  void write() {
    setup();
    write_static();
    std::size_t rows = 0;
    const std::vector<TrajectorySample>* clock_rows = nullptr;
    for (const BagRobot& b : robots_)
      if (b.run->trajectory.size() > rows) {
        rows = b.run->trajectory.size();
        clock_rows = &b.run->trajectory;
      }
    const std::uint16_t clock = channels_("/clock", "rosgraph_msgs/msg/Clock");
    const int crowd_every =
        std::max(1, static_cast<int>(std::lround(kCrowdMarkerPeriod / scenario_.sim.dt)));
    for (std::size_t k = 0; k < rows; ++k) {
      const std::uint64_t t = nanoseconds((*clock_rows)[k].t);
      encode_clock(w_, t);
      put(clock, t);
      for (RobotStream& r : streams_) write_row(r, k);
      if (crowd_ && !crowd_->empty() && k % static_cast<std::size_t>(crowd_every) == 0)
        write_crowd(t);
    }
    write_final_transitions();
    mcap_.finish();
  }

 private:
  void put(std::uint16_t channel, std::uint64_t t) { put(channel, t, w_.data()); }
  void put(std::uint16_t channel, std::uint64_t t, std::string_view data) {
    mcap_.write(channel, t, t, data);
  }

  void setup() {
    for (const BagRobot& b : robots_) {
      RobotStream r;
      r.robot = &b;
      // Sensor topics only for the ranges the run recorded (sim.record_ranges_every).
      if (!b.run->range_steps.empty())
        r.sensors = sensor_groups(b.task->robot, b, scenario_.sim.dt);
      r.goal_rows = goal_reached_rows(*b.task, *b.run);
      r.odom_frame = b.frame + "odom";
      r.base_frame = b.frame + "base_link";
      r.pose.emplace(r.odom_frame, r.base_frame);
      r.odom = channels_(b.topic + "/odom", "nav_msgs/msg/Odometry");
      r.tf = channels_(b.topic + "/tf", "tf2_msgs/msg/TFMessage");
      r.mode = channels_(b.topic + "/mode", "std_msgs/msg/String");
      r.transition = channels_(b.topic + "/transition", "std_msgs/msg/String");
      r.goal = channels_(b.topic + "/goal", "geometry_msgs/msg/PoseStamped");
      for (const SensorGroup& g : r.sensors)
        r.sensor_channels.push_back(channels_(g.topic, g.kind == SensorGroup::Single
                                                           ? "sensor_msgs/msg/Range"
                                                           : "sensor_msgs/msg/LaserScan"));
      streams_.push_back(std::move(r));
    }
  }

  /// At t = 0: the map, the world's shapes, each robot's static frames and its body.
  void write_static() {
    const WorldRaster m = world_raster(*scenario_.world);
    encode_occupancy_grid(w_, 0, "map", static_cast<float>(m.resolution),
                          static_cast<std::uint32_t>(m.width), static_cast<std::uint32_t>(m.height),
                          m.origin.position.x(), m.origin.position.y(), m.origin.theta, m.cells);
    put(channels_("/map", "nav_msgs/msg/OccupancyGrid"), 0);
    const std::vector<Ros2Marker> shapes = world_markers(*scenario_.world);
    encode_marker_array(w_, shapes);
    put(channels_("/world", "visualization_msgs/msg/MarkerArray"), 0);
    for (const RobotStream& r : streams_) {
      const BagRobot& b = *r.robot;
      std::vector<Ros2Transform> statics{{0, "map", r.odom_frame, 0.0, 0.0, 0.0}};
      for (const SensorGroup& g : r.sensors)
        if (g.frame != r.base_frame)
          statics.push_back({0, r.base_frame, g.frame, g.mount.position.x(), g.mount.position.y(),
                             g.mount.theta});
      encode_tf(w_, statics);
      put(channels_(b.topic + "/tf_static", "tf2_msgs/msg/TFMessage"), 0);
      Ros2Marker body;
      body.frame = r.base_frame;
      body.ns = "body";
      body.frame_locked = true;
      body.color = {0.2f, 0.45f, 0.85f, 0.8f};
      const RobotSpec& spec = b.task->robot;
      if (spec.footprint.empty()) {
        body.type = Ros2Marker::kCylinder;
        body.z = 0.05;
        body.scale = {2.0 * spec.body_radius, 2.0 * spec.body_radius, 0.1};
      } else {
        body.type = Ros2Marker::kLineStrip;
        body.scale = {0.02, 0.0, 0.0};
        for (const Vec2& p : spec.footprint) body.points.push_back({p.x(), p.y(), 0.0});
        body.points.push_back({spec.footprint.front().x(), spec.footprint.front().y(), 0.0});
      }
      const Ros2Marker markers[] = {body};
      encode_marker_array(w_, markers);
      put(channels_(b.topic + "/body", "visualization_msgs/msg/MarkerArray"), 0);
    }
  }

  void write_row(RobotStream& r, std::size_t k) {
    const RunResult& run = *r.robot->run;
    if (k >= run.trajectory.size()) return;
    const TrajectorySample& s = run.trajectory[k];
    const std::uint64_t t = nanoseconds(s.t);
    const Ros2Yaw yaw = ros2_yaw(s.theta);  // one sine and cosine for both messages
    put(r.tf, t, r.pose->tf(t, s.x, s.y, yaw));
    put(r.odom, t, r.pose->odometry(t, s.x, s.y, yaw, s.v, s.omega));
    if (s.mode != r.last_mode) {
      encode_string(w_, name_of(run.mode_names, s.mode, "mode_"));
      put(r.mode, t);
      r.last_mode = s.mode;
    }
    while (r.next_transition < run.transitions.size() &&
           nanoseconds(run.transitions[r.next_transition].time) <= t) {
      write_transition(r, run.transitions[r.next_transition++], t);
    }
    write_goal(r, k, t);
    // Sensor frames at most every kMcapSensorPeriod (a run may record more often, for its replay).
    while (r.next_frame < run.range_steps.size() &&
           static_cast<std::size_t>(run.range_steps[r.next_frame]) <= k) {
      if (static_cast<std::size_t>(run.range_steps[r.next_frame]) == k &&
          (!r.scanned || t + kPeriodSlack >= r.last_scan + kSensorPeriodNs)) {
        write_ranges(r, t);
        r.scanned = true;
        r.last_scan = t;
      }
      ++r.next_frame;
    }
  }

  /// A run's last transition (into `stop`, say) comes at the end of a step that records no row:
  /// it and the mode it enters, at its own time, after the last row, in time order.
  void write_final_transitions() {
    std::vector<std::pair<std::uint64_t, std::size_t>> left;  // time, stream
    for (std::size_t i = 0; i < streams_.size(); ++i) {
      const RobotStream& r = streams_[i];
      for (std::size_t k = r.next_transition; k < r.robot->run->transitions.size(); ++k)
        left.emplace_back(nanoseconds(r.robot->run->transitions[k].time), i);
    }
    std::stable_sort(left.begin(), left.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [t, i] : left) {
      RobotStream& r = streams_[i];
      const RunResult& run = *r.robot->run;
      const Transition& tr = run.transitions[r.next_transition++];
      write_transition(r, tr, t);
      if (tr.to != r.last_mode) {
        encode_string(w_, name_of(run.mode_names, tr.to, "mode_"));
        put(r.mode, t);
        r.last_mode = tr.to;
      }
    }
  }

  void write_transition(const RobotStream& r, const Transition& tr, std::uint64_t t) {
    const RunResult& run = *r.robot->run;
    std::string text = name_of(run.mode_names, tr.from, "mode_") + " -> " +
                       name_of(run.mode_names, tr.to, "mode_");
    if (tr.edge >= 0) text += ": " + name_of(run.guard_names, tr.edge, "edge_");
    encode_string(w_, text);
    put(r.transition, t);
  }

  /// The goal being driven to: the first at row 0, the next at the row the last was reached.
  void write_goal(RobotStream& r, std::size_t k, std::uint64_t t) {
    const auto& goals = r.robot->task->goals;
    const bool due = (k == 0 && !goals.empty()) ||
                     (r.next_goal > 0 && r.next_goal < goals.size() &&
                      r.goal_rows[r.next_goal - 1] == static_cast<std::int64_t>(k));
    if (!due) return;
    const Vec2& g = goals[r.next_goal];
    encode_pose_stamped(w_, t, "map", g.x(), g.y(), 0.0);
    put(r.goal, t);
    ++r.next_goal;
  }

  void write_ranges(RobotStream& r, std::uint64_t t) {
    const RunResult& run = *r.robot->run;
    const std::vector<RangeSensorSpec>& sensors = r.robot->task->robot.sensors;
    const std::size_t n = sensors.size();
    if (run.ranges.size() < (r.next_frame + 1) * n) return;
    const std::span<const float> frame(run.ranges.data() + r.next_frame * n, n);
    for (std::size_t gi = 0; gi < r.sensors.size(); ++gi) {
      const SensorGroup& g = r.sensors[gi];
      if (g.kind == SensorGroup::Lidar) {
        const std::span<const float> beams = frame.subspan(g.begin, g.end - g.begin);
        scan_.resize(beams.size());
        std::transform(beams.begin(), beams.end(), scan_.begin(),
                       [max = g.max_range](float r) { return r >= max ? kInf : r; });
        encode_laser_scan(w_, t, g.frame, g.shape, scan_);
      } else if (g.kind == SensorGroup::Ring) {
        ring(g, sensors, frame);
        encode_laser_scan(w_, t, g.frame, g.shape, scan_);
      } else {
        const RangeSensorSpec& spec = sensors[g.members[0]];
        const float v = frame[g.members[0]];
        encode_range(w_, t, g.frame,
                     spec.cone_angle > 0.0 ? Ros2Radiation::Ultrasound : Ros2Radiation::Infrared,
                     static_cast<float>(spec.cone_angle), static_cast<float>(spec.min_range),
                     static_cast<float>(spec.max_range), v >= spec.max_range ? kInf : v);
      }
      put(r.sensor_channels[gi], t);
    }
  }

  /// A ring's readings as seen from the robot's centre: each sensor's reading point (on its
  /// axis, from its mount) in the one-degree bin of its bearing, at its distance from the
  /// centre; a sensor that saw nothing marks its bin +inf (REP 117's "no return"), the other
  /// bins are NaN.
  void ring(const SensorGroup& g, const std::vector<RangeSensorSpec>& sensors,
            std::span<const float> frame) {
    scan_.assign(kRingBins, std::numeric_limits<float>::quiet_NaN());
    const double step = 2.0 * std::numbers::pi / kRingBins;
    for (std::size_t i : g.members) {
      const RangeSensorSpec& s = sensors[i];
      const bool seen = frame[i] < s.max_range;
      const double reach = seen ? frame[i] : s.max_range;
      const Vec2 p = s.mount.transform_point(Vec2(reach, 0.0));
      const double bearing = std::atan2(p.y(), p.x());
      const int bin = std::clamp(static_cast<int>(std::floor((bearing + std::numbers::pi) / step)),
                                 0, kRingBins - 1);
      float& cell = scan_[static_cast<std::size_t>(bin)];
      const float value = seen ? static_cast<float>(p.norm()) : kInf;
      if (std::isnan(cell) || value < cell) cell = value;
    }
  }

  void write_crowd(std::uint64_t t) {
    if (crowd_markers_.empty()) {
      crowd_cursor_.assign(crowd_->people.size() + crowd_->forklifts.size(), 0);
      crowd_channel_ = channels_("/crowd", "visualization_msgs/msg/MarkerArray");
    }
    crowd_markers_.clear();
    std::size_t k = 0;
    const auto add = [&](const CrowdTrack& track, int id, bool forklift) {
      std::size_t& j = crowd_cursor_[k++];
      if (track.samples.empty()) return;
      while (j + 1 < track.samples.size() && nanoseconds(track.samples[j + 1].t) <= t) ++j;
      const CrowdSample& s = track.samples[j];
      Ros2Marker m;
      m.stamp = t;
      m.frame = "map";
      m.ns = forklift ? "forklifts" : "people";
      m.id = id;
      m.type = forklift ? Ros2Marker::kCube : Ros2Marker::kCylinder;
      m.x = s.x;
      m.y = s.y;
      m.yaw = s.theta;
      const double height = forklift ? 1.0 : 1.7;
      m.z = 0.5 * height;
      m.scale = {track.size.x(), track.size.y(), height};
      m.color = forklift ? std::array<float, 4>{0.95f, 0.6f, 0.1f, 0.9f}
                         : std::array<float, 4>{0.85f, 0.3f, 0.55f, 0.9f};
      crowd_markers_.push_back(std::move(m));
    };
    for (std::size_t i = 0; i < crowd_->people.size(); ++i)
      add(crowd_->people[i], static_cast<int>(i), false);
    for (std::size_t i = 0; i < crowd_->forklifts.size(); ++i)
      add(crowd_->forklifts[i], static_cast<int>(i), true);
    encode_marker_array(w_, crowd_markers_);
    put(crowd_channel_, t);
  }

  static std::string name_of(const std::vector<std::string>& names, int i, const char* fallback) {
    return i >= 0 && static_cast<std::size_t>(i) < names.size() ? names[static_cast<std::size_t>(i)]
                                                                : fmt::format("{}{}", fallback, i);
  }

  const Scenario& scenario_;
  std::vector<BagRobot> robots_;
  const CrowdResult* crowd_;
  McapWriter mcap_;
  Channels channels_;
  CdrWriter w_;
  std::vector<RobotStream> streams_;
  std::vector<float> scan_;
  std::vector<Ros2Marker> crowd_markers_;
  std::vector<std::size_t> crowd_cursor_;
  std::uint16_t crowd_channel_{0};
};

}  // namespace

int mcap_ranges_interval(const Scenario& s) {
  const int within = ranges_interval_within(s, kMaxMcapRangeValues);
  if (within == 0) return 0;
  const double rate = std::round(kMcapSensorPeriod / s.sim.dt);
  return std::max(within, static_cast<int>(std::clamp(rate, 1.0, 1e9)));
}

void write_run_mcap(const Scenario& scenario, const RunResult& result, const McapSink& sink) {
  BagWriter(scenario, {{&scenario.robot(), &result, "", ""}}, nullptr, sink).write();
}

void write_fleet_mcap(const Scenario& scenario, const FleetResult& result, const McapSink& sink) {
  std::vector<BagRobot> robots;
  for (std::size_t i = 0; i < result.robots.size() && i < scenario.robots.size(); ++i) {
    const std::string& name = scenario.robots[i].name;
    robots.push_back({&scenario.robots[i], &result.robots[i], "/" + name, name + "/"});
  }
  BagWriter(scenario, std::move(robots), &result.crowd, sink).write();
}

}  // namespace floornav
