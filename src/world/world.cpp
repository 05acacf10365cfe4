#include "floornav/world/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "floornav/geometry/polygon.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/world/occupancy_grid.hpp"

// The world as described: its shapes, its extent, and whether a point lies inside an obstacle.
// (The spatial index that the queries walk: world_index.cpp; fans of rays: world_fan.cpp.)

namespace floornav {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

void grow(Box2& b, bool& empty, const Vec2& lo, const Vec2& hi) {
  if (empty) {
    b = {lo, hi};
    empty = false;
  } else {
    b.min = b.min.cwiseMin(lo);
    b.max = b.max.cwiseMax(hi);
  }
}

}  // namespace

World::World(WorldDesc desc)
    : bounds_(desc.bounds),
      circles_(std::move(desc.circles)),
      polygons_(std::move(desc.polygons)),
      grid_(std::move(desc.grid)) {
  if (bounds_) {
    const Vec2 a = bounds_->min, c = bounds_->max;
    const Vec2 b(c.x(), a.y()), d(a.x(), c.y());
    segments_.insert(segments_.end(), {Segment{a, b}, Segment{b, c}, Segment{c, d}, Segment{d, a}});
    solid_sides_.assign(4, -1.0);  // counter-clockwise, solid outside
  } else if (grid_) {
    // A map without bounds is the whole world: off the map is not known to be free, so its edge
    // is a wall like the bounds' (a robot never drives round a wall by leaving the map).
    const double w = grid_->width() * grid_->resolution(),
                 h = grid_->height() * grid_->resolution();
    const Pose2& o = grid_->origin();
    map_edge_ = {o.transform_point({0.0, 0.0}), o.transform_point({w, 0.0}),
                 o.transform_point({w, h}), o.transform_point({0.0, h})};
    for (std::size_t i = 0; i < map_edge_.size(); ++i) segments_.push_back(edge(map_edge_, i));
    solid_sides_.assign(map_edge_.size(), -1.0);  // counter-clockwise, solid outside
    map_edge_box_ = box_of(map_edge_);
  }
  for (const auto& poly : polygons_) {
    for (std::size_t i = 0; i < poly.size(); ++i) segments_.push_back(edge(poly, i));
    // A simple polygon is solid on the side its winding turns to; a degenerate one (zero area)
    // has no known side.
    const double area = signed_area(poly);
    solid_sides_.resize(segments_.size(), area > 0.0 ? 1.0 : (area < 0.0 ? -1.0 : 0.0));
    polygon_boxes_.push_back(box_of(poly));
  }
  bool empty = true;
  if (bounds_) grow(extent_, empty, bounds_->min, bounds_->max);
  for (const Circle& c : circles_) {
    const Vec2 r(c.radius, c.radius);
    grow(extent_, empty, c.center - r, c.center + r);
  }
  for (const Box2& b : polygon_boxes_) grow(extent_, empty, b.min, b.max);
  if (grid_) {
    Vec2 lo, hi;
    grid_->world_extent(&lo, &hi);
    grow(extent_, empty, lo, hi);
  }
  build_index();
}

bool World::inside_solid_shape(const Vec2& p) const {
  if (bounds_ && !bounds_->contains(p)) return true;
  if (!map_edge_.empty() && (!map_edge_box_.contains(p) || !contains(map_edge_, p))) return true;
  if (!extent_.contains(p)) return false;
  const std::size_t c = static_cast<std::size_t>(cell_y(p.y())) * index_.nx + cell_x(p.x());
  for (std::uint32_t k = index_.circle_offsets[c]; k < index_.circle_offsets[c + 1]; ++k) {
    if (signed_distance(circles_[index_.circle_items[k]], p) <= 0.0) return true;
  }
  for (std::uint32_t k = index_.polygon_offsets[c]; k < index_.polygon_offsets[c + 1]; ++k) {
    const std::uint32_t i = index_.polygon_items[k];
    if (polygon_boxes_[i].contains(p) && contains(polygons_[i], p)) return true;
  }
  return false;
}

bool World::is_inside_obstacle(const Vec2& p) const {
  if (inside_solid_shape(p)) return true;
  return grid_ != nullptr && grid_->clearance(p) <= 0.0;
}

double World::cast_ray_brute_force(const Vec2& origin, const Vec2& dir, double max_range) const {
  double best = max_range;
  if (grid_) best = std::min(best, grid_->cast_ray(origin, dir, max_range));
  if (inside_solid_shape(origin)) return 0.0;
  for (const Segment& s : segments_)
    if (auto t = intersect_ray(s, origin, dir); t && *t < best) best = *t;
  for (const Circle& c : circles_)
    if (auto t = intersect_ray(c, origin, dir); t && *t < best) best = *t;
  return best;
}

double World::clearance_brute_force(const Vec2& p) const {
  double d = kInf;
  for (const Segment& s : segments_) d = std::min(d, distance(s, p));
  for (const Circle& c : circles_) d = std::min(d, std::abs(signed_distance(c, p)));
  if (d < kInf && inside_solid_shape(p)) d = -d;
  if (grid_) d = std::min(d, grid_->clearance(p));
  return d;
}

}  // namespace floornav
