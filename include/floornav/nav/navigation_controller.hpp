#pragma once
/// @file
/// The four built-in controller kinds as Controllers: each step builds the navigation input
/// from what the robot sensed (navigation_input.hpp), steps its automaton
/// (navigation_automaton.hpp) and hands the mode's velocity u to the pipeline of Fig 5.12.

#include <memory>
#include <vector>

#include "floornav/nav/controller.hpp"
#include "floornav/nav/navigation_automaton.hpp"

namespace floornav {

class NavigationController final : public Controller {
 public:
  /// `automaton` may be shared by many robots (it is immutable); `params` must be the ones it
  /// was built with.
  NavigationController(std::shared_ptr<const NavigationAutomaton> automaton,
                       const NavigationParams& params);

  Decision decide(const Observation& obs) override;
  void reset() override { state_ = automaton_->initial_state(); }
  int mode() const override { return state_.mode; }

  const NavigationAutomaton& automaton() const { return *automaton_; }
  const NavigationAutomaton::State& state() const { return state_; }

 private:
  std::shared_ptr<const NavigationAutomaton> automaton_;
  NavigationParams params_;
  NavigationAutomaton::State state_;
};

/// The built-in controller of `config.kind` (which must name one: see parse_controller_kind).
std::unique_ptr<Controller> make_builtin_controller(const ControllerConfig& config);

class KnownMapRasters;

/// Makes the controllers of many robots: a user's factory is called per robot; robots of one
/// built-in kind with equal parameters share one automaton (100,000 robots, one automaton).
/// `dwa` makes a DwaController; a `planner.kind` other than none wraps the reactive controller
/// in a PlannerController (planner_controller.hpp), and robots planning on one known map share
/// its raster. With `params.robot_avoidance` set, the whole is wrapped in that layer
/// (robot_avoidance.hpp).
class ControllerMaker {
 public:
  ControllerMaker();
  ~ControllerMaker();
  std::unique_ptr<Controller> make(const ControllerConfig& config,
                                   const ControllerContext& context);

 private:
  std::unique_ptr<Controller> make_planned(const ControllerConfig& config,
                                           const ControllerContext& context);
  std::unique_ptr<Controller> make_reactive(const ControllerConfig& config,
                                            const ControllerContext& context);
  std::shared_ptr<KnownMapRasters> rasters_;
  struct Built {
    ControllerKind kind;
    NavigationParams params;
    std::shared_ptr<const NavigationAutomaton> automaton;
  };
  std::vector<Built> built_;
};

}  // namespace floornav
