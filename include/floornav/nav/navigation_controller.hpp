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

/// Built chapter automata, by kind and parameters: robots of one kind with equal parameters
/// share one (100,000 robots, one automaton).
class SharedAutomata {
 public:
  std::shared_ptr<const NavigationAutomaton> get(ControllerKind kind, const NavigationParams& p);

 private:
  struct Built {
    ControllerKind kind;
    NavigationParams params;
    std::shared_ptr<const NavigationAutomaton> automaton;
  };
  std::vector<Built> built_;
};

/// The built-in controller that `config.kind` names (nav/controller_registry.hpp) for the robot of
/// `context`, alone: no planning layer, no robot avoidance. Throws std::invalid_argument when
/// the kind is not built in.
std::unique_ptr<Controller> make_builtin_controller(const ControllerConfig& config,
                                                    const ControllerContext& context);

class KnownMapRasters;

/// Whether the controllers `config` makes may read Observation::beams, ::ranges and ::sensed: a
/// user's controller may, and so does the planning layer (its rolling grid); the built-in kinds
/// and robot avoidance read the points alone.
bool controller_reads_frames(const ControllerConfig& config);

/// Makes the controllers of many robots: a user's factory is called per robot; a built-in kind
/// comes from the registry (controller_registry.hpp), its robots sharing automata. A
/// `planner.kind` other than none wraps the controller in a PlannerController
/// (planner_controller.hpp), and robots planning on one known map share its raster. With
/// `avoidance.kind` orca, the whole is wrapped in that layer (robot_avoidance.hpp).
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
  SharedAutomata automata_;
};

}  // namespace floornav
