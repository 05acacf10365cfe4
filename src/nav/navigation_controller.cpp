#include "floornav/nav/navigation_controller.hpp"

#include <algorithm>
#include <stdexcept>

#include "floornav/nav/controller_registry.hpp"
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

std::shared_ptr<const NavigationAutomaton> SharedAutomata::get(ControllerKind kind,
                                                               const NavigationParams& p) {
  for (const Built& b : built_)
    if (b.kind == kind && b.params == p) return b.automaton;
  built_.push_back(
      {kind, p, std::make_shared<const NavigationAutomaton>(make_navigation_automaton(kind, p))});
  return built_.back().automaton;
}

namespace {
const BuiltinController& builtin_of(const ControllerConfig& config) {
  const BuiltinController* builtin = find_builtin_controller(config.kind);
  if (!builtin)
    throw std::invalid_argument("'" + config.kind +
                                "' is no built-in controller kind, and no factory is given");
  return *builtin;
}
}  // namespace

std::unique_ptr<Controller> make_builtin_controller(const ControllerConfig& config,
                                                    const ControllerContext& context) {
  SharedAutomata automata;
  return builtin_of(config).make(config, context, automata);
}

ControllerMaker::ControllerMaker() = default;
ControllerMaker::~ControllerMaker() = default;

bool controller_reads_frames(const ControllerConfig& config) {
  return !config.is_builtin() || config.planner.kind != PlannerKind::None;
}

std::unique_ptr<Controller> ControllerMaker::make(const ControllerConfig& config,
                                                  const ControllerContext& context) {
  auto controller = make_planned(config, context);
  // Robot avoidance is the outermost layer: it bends whatever velocity the controller wants.
  if (config.avoidance.kind == RobotAvoidance::Orca)
    return make_orca_layer(std::move(controller), context.robot, config.avoidance,
                           controller_reads_frames(config));
  return controller;
}

std::unique_ptr<Controller> ControllerMaker::make_planned(const ControllerConfig& config,
                                                          const ControllerContext& context) {
  if (config.planner.kind == PlannerKind::None || config.factory)
    return make_reactive(config, context);
  // The planning layer over the reactive kind. The inner automaton's goal radius shrinks: its
  // goals are subgoals, and the planner itself stops at the real goal's epsilon.
  ControllerConfig inner = config;
  inner.planner = PlannerParams{};
  inner.params.epsilon = std::min(config.params.epsilon, 0.5 * context.robot.body_radius);
  // "Clear shot" (eq. 5.27) becomes a free corridor to the subgoal (the clear_shot_corridor
  // extension): a wall beside the planned way is not in the way, only what lies across it.
  if (!(inner.params.clear_shot_corridor > 0.0)) {
    const PlannerParams& pp = config.planner;
    inner.params.clear_shot_corridor =
        pp.lookahead > 0.0 ? pp.lookahead : 6.0 * context.robot.body_radius;
  }
  if (!rasters_) rasters_ = std::make_shared<KnownMapRasters>();
  PlannerController::Setup setup;
  setup.inner = make_reactive(inner, context);
  setup.params = config.params;
  setup.planner = config.planner;
  setup.robot = &context.robot;
  setup.map = context.map;
  setup.rasters = rasters_;
  setup.seed = context.seed;
  return std::make_unique<PlannerController>(std::move(setup));
}

std::unique_ptr<Controller> ControllerMaker::make_reactive(const ControllerConfig& config,
                                                           const ControllerContext& context) {
  if (config.factory) {
    auto controller = config.factory(context);
    if (!controller)
      throw std::invalid_argument("the factory of controller '" + config.kind +
                                  "' made no controller");
    return controller;
  }
  return builtin_of(config).make(config, context, automata_);
}

}  // namespace floornav
