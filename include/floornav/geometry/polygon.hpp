#pragma once
/// @file
/// Simple polygons of either winding, convex or concave (section 5.4.2, Practice 1).

#include <span>
#include <vector>

#include "floornav/geometry/segment.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// The signed area (m^2) of the closed polygon `v`: > 0 for counter-clockwise.
double signed_area(std::span<const Vec2> v);

/// True when every segment between two points of the polygon lies inside it (Practice 1):
/// for a simple polygon, when all turns have the same sign. Collinear vertices are allowed.
bool is_convex(std::span<const Vec2> v);

/// True when no two non-adjacent edges meet and no edge has zero length.
bool is_simple(std::span<const Vec2> v);

/// Even-odd point-in-polygon test; points on the boundary count as inside.
bool contains(std::span<const Vec2> v, const Vec2& p);

/// Edge `i` of the closed polygon: from v[i] to v[(i+1) % n].
inline Segment edge(std::span<const Vec2> v, std::size_t i) {
  return {v[i], v[(i + 1) % v.size()]};
}

/// Distance from `p` to the polygon's boundary (unsigned).
double boundary_distance(std::span<const Vec2> v, const Vec2& p);

/// A rectangle of the given size, centred at `center`, rotated by `angle` (counter-clockwise).
std::vector<Vec2> make_rectangle(const Vec2& center, const Vec2& size, double angle);

}  // namespace floornav
