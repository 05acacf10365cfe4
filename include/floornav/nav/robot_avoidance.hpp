#pragma once
/// @file
/// Robot-robot avoidance for fleets: a reciprocal-velocity layer (ORCA, "optimal reciprocal
/// collision avoidance": J. van den Berg, S. J. Guy, M. Lin, D. Manocha, "Reciprocal n-body
/// collision avoidance", ISRR 2009 / Springer STAR 70, 2011) between a robot's controller and its
/// wheels. The chapter's automaton assumes still obstacles; two robots that follow one boundary in
/// opposite directions meet head on, each waiting for the other to move. With
/// `controller.robot_avoidance: orca`:
///   - the other robots that are moving and near (Observation::robots: told, not sensed) are taken
///     out of what the controller sees (their sensed returns, and the remembered returns along
///     the way they came), so the automaton deals with the still world alone;
///   - the controller's velocity u is then the preferred velocity of ORCA: the velocity nearest
///     to u that takes half the effort of avoiding each moving robot within `avoidance_horizon`
///     (each robot assumes the other does the other half), and that does not drive at any other
///     sensed point (walls, parked robots, people) faster than its clearance allows in 0.5 s.
/// Robots that have finished (parked) stay obstacles like any other. With no moving robot near,
/// the layer does nothing at all: a lone robot runs exactly as without it. Commands other than a
/// velocity u (unicycle, wheels, goal reached) pass unchanged.
///
/// Written here rather than taken from a library: RVO2 (the authors' C++ library) has no Debian
/// package. The linear programs follow the paper's section 5 (and RVO2's structure).

#include <memory>
#include <span>
#include <vector>

#include "floornav/geometry/vec2.hpp"
#include "floornav/nav/controller.hpp"
#include "floornav/nav/robot_avoidance_params.hpp"

namespace floornav {

/// The permitted velocities of one ORCA constraint: the half-plane to the left of `direction`
/// (a unit vector) through `point`.
struct OrcaLine {
  Vec2 point{Vec2::Zero()};
  Vec2 direction{1.0, 0.0};
};

/// ORCA's constraint for agent A against agent B (paper, eq. 6 and Fig 3): with p = p_B - p_A and
/// the relative velocity v = v_A - v_B, u is the smallest change of v that leaves the velocity
/// obstacle VO^tau (the truncated cone of velocities that collide within tau: the disc of radius
/// r = r_A + r_B centred at p / tau, and its tangent legs); A takes `responsibility` of u (1/2
/// when B avoids as well, 1 when it does not) and the half-plane through v_A + responsibility u,
/// normal to u. Already overlapping (|p| <= r), the step `dt` takes tau's place, to separate
/// within one step.
OrcaLine orca_line(const Vec2& p, const Vec2& v_a, const Vec2& v_b, double r, double tau, double dt,
                   double responsibility);

/// A still point at `p` (relative to A) that A must not approach faster than its clearance
/// allows within tau: v . p/|p| <= max(|p| - r, 0) / tau. The origin is always permitted.
OrcaLine still_point_line(const Vec2& p, double r, double tau);

/// Reusable working memory of the linear programs (grows, never shrinks: no allocation in steady
/// state).
struct OrcaScratch {
  std::vector<OrcaLine> lines;
  std::vector<OrcaLine> projected;
};

/// The velocity nearest to `preferred` within speed `max_speed` that satisfies every line
/// (the paper's linear program, section 5.2: an incremental 2D program over the lines, the first
/// `hard` of which are never relaxed). When the lines leave no room, the velocity that violates
/// the soft lines (those after `hard`) least, in the worst case (the paper's 3D program).
/// `lines` are the hard lines first; `scratch.projected` is working memory.
Vec2 solve_orca(std::span<const OrcaLine> lines, std::size_t hard, const Vec2& preferred,
                double max_speed, std::vector<OrcaLine>& projected);

/// How far from a moving robot's body disc a return may lie and still be taken for the robot's
/// (rounding, and four standard deviations of the robot's sensor noise), m.
double robot_return_tolerance(const RobotSpec& robot);

/// Writes to `out` the points of `points` that belong to no moving robot of `robots` (lie
/// farther than its radius + `tolerance` from its centre); returns how many.
std::size_t drop_robot_points(std::span<const Vec2> points, std::span<const NearbyRobot> robots,
                              double tolerance, std::span<Vec2> out);

/// Wraps a controller with the ORCA layer above (`params.kind` is not looked at: the caller
/// chose the layer). `robot` sizes the buffers once (no allocation per step). The wrapped
/// controller's modes and guards are reported unchanged. `inner_reads_sensed` false: the wrapped
/// controller reads Observation::points alone, never ::sensed (the built-in kinds), so the moving
/// robots' returns are taken out only when the points are the returns (remembered points hold
/// none of them).
std::unique_ptr<Controller> make_orca_layer(std::unique_ptr<Controller> inner,
                                            const RobotSpec& robot,
                                            const RobotAvoidanceParams& params,
                                            bool inner_reads_sensed = true);

}  // namespace floornav
