#include "floornav/nav/navigation_controller.hpp"

#include <stdexcept>

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
  return std::make_unique<NavigationController>(
      std::make_shared<const NavigationAutomaton>(
          make_navigation_automaton(builtin_kind(config), config.params)),
      config.params);
}

std::unique_ptr<Controller> ControllerMaker::make(const ControllerConfig& config,
                                                  const ControllerContext& context) {
  auto controller = make_bare(config, context);
  if (config.params.robot_avoidance == RobotAvoidance::Orca)
    return make_orca_layer(std::move(controller), context.robot);
  return controller;
}

std::unique_ptr<Controller> ControllerMaker::make_bare(const ControllerConfig& config,
                                                       const ControllerContext& context) {
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
