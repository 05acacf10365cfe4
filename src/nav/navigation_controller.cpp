#include "floornav/nav/navigation_controller.hpp"

#include <algorithm>
#include <stdexcept>

#include "floornav/nav/dwa_controller.hpp"
#include "floornav/nav/planner_controller.hpp"
#include "floornav/nav/robot_avoidance.hpp"

namespace floornav {

namespace {
std::vector<std::string> mode_names_of(const NavigationAutomaton& a) {
  std::vector<std::string> names;
  for (const auto& m : a.modes()) names.push_back(m.name);
  return names;
}
std::vector<std::string> guard_names_of(const NavigationAutomaton& a) {
  std::vector<std::string> names;
  for (const auto& e : a.edges()) names.push_back(e.guard_name);
  return names;
}
}  // namespace

NavigationController::NavigationController(std::shared_ptr<const NavigationAutomaton> automaton,
                                           const NavigationParams& params)
    : Controller(mode_names_of(*automaton), guard_names_of(*automaton)),
      automaton_(std::move(automaton)),
      params_(params),
      state_(automaton_->initial_state()) {}

Decision NavigationController::decide(const Observation& obs) {
  // 2. supervise: at most one guarded transition, then the mode's flow (step 3 of the pipeline
  // is the simulator's: u -> theta_d -> omega -> wheels).
  const BodyShape shape{obs.robot->footprint, obs.pose.theta};
  const NavigationInput in = make_navigation_input(obs.pose.position, obs.goal, obs.points,
                                                   obs.robot->body_radius, params_, &shape);
  const auto tr = automaton_->step(in, state_, obs.t + obs.dt, obs.dt);
  const int guard = tr ? tr->edge : -1;
  if (automaton_->is_terminal(state_)) return {Command::goal_reached(), state_.mode, guard};
  return {Command::velocity(automaton_->flow(in, state_)), state_.mode, guard};
}

namespace {
ControllerKind builtin_kind(const ControllerConfig& config) {
  const auto kind = parse_controller_kind(config.kind);
  if (!kind)
    throw std::invalid_argument("'" + config.kind +
                                "' is no built-in controller kind, and no factory is given");
  return *kind;
}
}  // namespace

std::unique_ptr<Controller> make_builtin_controller(const ControllerConfig& config) {
  if (config.kind == kDwaKindName)
    throw std::invalid_argument("the dwa controller needs its robot: use ControllerMaker");
  return std::make_unique<NavigationController>(
      std::make_shared<const NavigationAutomaton>(
          make_navigation_automaton(builtin_kind(config), config.params)),
      config.params);
}

ControllerMaker::ControllerMaker() = default;
ControllerMaker::~ControllerMaker() = default;

std::unique_ptr<Controller> ControllerMaker::make(const ControllerConfig& config,
                                                  const ControllerContext& context) {
  auto controller = make_planned(config, context);
  // Robot avoidance is the outermost layer: it bends whatever velocity the controller wants.
  if (config.params.robot_avoidance == RobotAvoidance::Orca)
    return make_orca_layer(std::move(controller), context.robot);
  return controller;
}

std::unique_ptr<Controller> ControllerMaker::make_planned(const ControllerConfig& config,
                                                          const ControllerContext& context) {
  if (config.params.planner.kind == PlannerKind::None || config.factory)
    return make_reactive(config, context);
  // The planning layer over the reactive kind. The inner automaton's goal radius shrinks: its
  // goals are subgoals, and the planner itself stops at the real goal's epsilon.
  ControllerConfig inner = config;
  inner.params.planner = PlannerParams{};
  inner.params.epsilon = std::min(config.params.epsilon, 0.5 * context.robot.body_radius);
  // "Clear shot" (eq. 5.27) becomes a free corridor to the subgoal (the clear_shot_corridor
  // extension): a wall beside the planned way is not in the way, only what lies across it.
  if (!(inner.params.clear_shot_corridor > 0.0)) {
    const PlannerParams& pp = config.params.planner;
    inner.params.clear_shot_corridor =
        pp.lookahead > 0.0 ? pp.lookahead : 6.0 * context.robot.body_radius;
  }
  if (!rasters_) rasters_ = std::make_shared<KnownMapRasters>();
  PlannerController::Setup setup;
  setup.inner = make_reactive(inner, context);
  setup.params = config.params;
  setup.robot = &context.robot;
  setup.map = context.map;
  setup.rasters = rasters_;
  setup.seed = context.seed;
  return std::make_unique<PlannerController>(std::move(setup));
}

std::unique_ptr<Controller> ControllerMaker::make_reactive(const ControllerConfig& config,
                                                           const ControllerContext& context) {
  if (config.kind == kDwaKindName && !config.factory)
    return std::make_unique<DwaController>(config.params, context.robot);
  if (config.factory) {
    auto controller = config.factory(context);
    if (!controller)
      throw std::invalid_argument("the factory of controller '" + config.kind +
                                  "' made no controller");
    return controller;
  }
  const ControllerKind kind = builtin_kind(config);
  for (const Built& b : built_)
    if (b.kind == kind && b.params == config.params)
      return std::make_unique<NavigationController>(b.automaton, config.params);
  built_.push_back({kind, config.params,
                    std::make_shared<const NavigationAutomaton>(
                        make_navigation_automaton(kind, config.params))});
  return std::make_unique<NavigationController>(built_.back().automaton, config.params);
}

}  // namespace floornav
