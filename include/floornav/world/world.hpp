#pragma once
/// @file
/// The static obstacle world: walls, circles and polygons, behind a uniform-grid spatial index so
/// that ray casts and clearance queries cost about the same for 10 edges or 10,000.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "floornav/geometry/box2.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/segment.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/world/fan_scratch.hpp"

namespace floornav {

class OccupancyGrid;

/// What World::clearance learnt at a point, kept by a caller that queries again nearby (a robot
/// checking its body every step): the two nearest items (two, since a polygon's corner is the
/// nearest point of both its edges) and a lower bound on every other item's distance. Distances
/// change by at most the distance moved, so while the two stay nearer than that bound allows any
/// other to come, they alone give the answer, bit for bit the full search's. Worlds with an
/// occupancy grid are always searched in full.
struct ClearanceHint {
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  Vec2 at{Vec2::Zero()};  ///< where the last full search was made
  /// The nearest items there: segment index, or circle index + segment count; kNone: no item.
  std::array<std::uint32_t, 2> nearest{kNone, kNone};
  double runner_up{0.0};  ///< m, lower bound at `at` on the distance of every other item
  bool valid{false};      ///< false: no search yet, or none that can be reused
};

/// What a world is made of, as a user describes it. Polygons may wind either way, but must be
/// simple (the scenario readers check it): a cast tests only the edges that face its origin, the
/// side a polygon's winding makes free.
struct WorldDesc {
  std::optional<Box2> bounds;                 ///< walls on all four sides; outside is solid
  std::vector<Circle> circles;                ///< solid discs (radius 0: a point obstacle)
  std::vector<std::vector<Vec2>> polygons;    ///< solid simple polygons, convex or concave
  std::shared_ptr<const OccupancyGrid> grid;  ///< optional occupancy map (the World keeps it)
};

/// Immutable obstacle world. Queries are `const` and thread-safe.
class World {
 public:
  explicit World(WorldDesc desc);

  /// Distance from `origin` along unit `dir` to the first obstacle surface, or `max_range` when
  /// nothing is hit closer. 0 when `origin` is inside an obstacle.
  double cast_ray(const Vec2& origin, const Vec2& dir, double max_range) const;

  /// `cast_ray` for an `origin` the caller knows to lie outside every obstacle shape (circles,
  /// polygons, bounds; the occupancy grid is still checked), e.g. because it is nearer than
  /// `clearance(c)` to a point `c`. Skips the inside test, so a fan of rays pays for it once.
  /// The result is bit for bit that of `cast_ray`.
  double cast_ray_from_free(const Vec2& origin, const Vec2& dir, double max_range) const;

  /// Casts a fan of rays from one `origin`: `out[i]` is bit for bit
  /// `cast_ray(origin, dirs[i], max_range)`. `angles[i]` is the angle of `dirs[i]` to within
  /// 1e-9 rad (the theta of dir = (cos theta, sin theta)). When the angles are evenly spaced (a
  /// lidar), the obstacles within `max_range` are gathered once and each is tested only against
  /// the rays its angular extent covers (with a margin far above rounding); any other fan is cast
  /// ray by ray. The three spans have the same size. Works in `scratch` (see FanScratch): no
  /// allocation once it has grown to the fan and the world. With `spacing_known`, the caller
  /// vouches that the angles are evenly spaced (each within 1e-9 rad of angles[0] + k (angles[1]
  /// - angles[0]), as a lidar's beams are), and the per-beam check of that is skipped.
  void cast_fan(const Vec2& origin, std::span<const Vec2> dirs, std::span<const double> angles,
                double max_range, std::span<double> out, FanScratch& scratch,
                bool spacing_known = false) const;
  /// `cast_fan` with scratch memory of its own (allocated per call).
  void cast_fan(const Vec2& origin, std::span<const Vec2> dirs, std::span<const double> angles,
                double max_range, std::span<double> out) const;

  /// `cast_fan` for an `origin` known to be free, as for `cast_ray_from_free`; bit for bit
  /// `cast_ray_from_free` per ray.
  void cast_fan_from_free(const Vec2& origin, std::span<const Vec2> dirs,
                          std::span<const double> angles, double max_range, std::span<double> out,
                          FanScratch& scratch, bool spacing_known = false) const;

  /// Signed distance from `p` to the nearest obstacle surface: negative inside an obstacle or
  /// outside the bounds (or, for a map without bounds, off the map: its edge is a wall).
  /// +infinity in an empty, unbounded world.
  double clearance(const Vec2& p) const;
  /// `clearance(p)`, bit for bit, reusing and then updating `hint` (see ClearanceHint).
  double clearance(const Vec2& p, ClearanceHint& hint) const;

  /// Signed distance between the solid polygon `poly` (world frame, e.g. a robot footprint) and
  /// the obstacles: <= 0 when they touch or overlap. Exact up to `reach` metres; beyond it the
  /// result is a lower bound of at least `reach`. Occupancy grids count by the polygon's
  /// circumscribed disc.
  double polygon_clearance(std::span<const Vec2> poly, double reach) const;

  /// True when `p` is inside an obstacle (or outside the bounds).
  bool is_inside_obstacle(const Vec2& p) const;

  /// Brute-force versions of the queries above, the oracle for tests.
  double cast_ray_brute_force(const Vec2& origin, const Vec2& dir, double max_range) const;
  double clearance_brute_force(const Vec2& p) const;

  const std::optional<Box2>& bounds() const { return bounds_; }
  std::span<const Circle> circles() const { return circles_; }
  std::span<const Segment> segments() const { return segments_; }  ///< walls + polygon edges
  const std::vector<std::vector<Vec2>>& polygons() const { return polygons_; }
  const OccupancyGrid* grid() const { return grid_.get(); }
  /// The outline of a map that has no bounds (its four corners, counter-clockwise): off the map
  /// is solid, as outside the bounds is. Empty when the world has bounds or no map.
  std::span<const Vec2> map_edge() const { return map_edge_; }
  const std::shared_ptr<const OccupancyGrid>& shared_grid() const { return grid_; }
  /// The box that holds every obstacle and the bounds (empty box for an empty world).
  const Box2& extent() const { return extent_; }
  std::size_t edge_count() const { return segments_.size(); }

 private:
  /// A segment as the ray test reads it (hot data, 64 bytes): start point, edge vector b - a,
  /// and bounding box.
  struct SegmentRay {
    Vec2 a{Vec2::Zero()};
    Vec2 e{Vec2::Zero()};
    Vec2 lo{Vec2::Zero()};
    Vec2 hi{Vec2::Zero()};
  };
  struct Index {
    Vec2 origin{Vec2::Zero()};
    double cell{1.0};
    double inv_cell{1.0};
    int nx{0};
    int ny{0};
    // Compressed rows: items of cell c are [offsets[c], offsets[c+1]) in each list.
    std::vector<std::uint32_t> segment_offsets, segment_items;
    std::vector<SegmentRay> segment_rays;  ///< segments_[segment_items[k]], copied in cell order
    std::vector<double> segment_sides;     ///< solid_sides_[segment_items[k]], in the same order
    std::vector<std::uint32_t> circle_offsets, circle_items;
    std::vector<std::uint32_t> polygon_offsets, polygon_items;
  };

  void build_index();
  /// clearance() of the segments and circles alone (the grid left out); with kHint, also fills
  /// `hint` (a template so that the plain query keeps its lean loop).
  template <bool kHint>
  double shape_clearance(const Vec2& p, ClearanceHint* hint) const;
  bool inside_solid_shape(const Vec2& p) const;
  int cell_x(double x) const;
  int cell_y(double y) const;
  /// Smallest hit distance among the items of one cell, below `best`. With `ray_box` (the ray's
  /// box up to `best`, with a margin), segments whose boxes miss it are skipped untested.
  double ray_in_cell(int cell, const Vec2& origin, const Vec2& dir, double best,
                     const Box2* ray_box = nullptr) const;

  std::optional<Box2> bounds_;
  /// The map's outline (its corners, counter-clockwise) when the world is a map without bounds:
  /// a wall, outside of which is solid, as outside the bounds is. Empty otherwise.
  std::vector<Vec2> map_edge_;
  Box2 map_edge_box_;
  std::vector<Circle> circles_;
  std::vector<Segment> segments_;
  /// Per segment, which side of it is solid: +1 the left of a -> b (a counter-clockwise polygon's
  /// edge), -1 the right (a clockwise polygon's, the bounds' and the map edge's), 0 neither
  /// known. A ray from a free point first meets a solid on an edge whose solid side faces away
  /// from it, so edges seen from their solid side are not tested (see seen_from_solid_side).
  std::vector<double> solid_sides_;
  std::vector<std::vector<Vec2>> polygons_;
  std::vector<Box2> polygon_boxes_;
  std::shared_ptr<const OccupancyGrid> grid_;
  Box2 extent_;
  Index index_;
};

}  // namespace floornav
