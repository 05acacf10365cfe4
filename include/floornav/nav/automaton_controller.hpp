#pragma once
/// @file
/// A user's own hybrid automaton as a Controller: the engine of automaton/hybrid_automaton.hpp
/// with the Observation as its input and a Command as each mode's flow, so that guards read what
/// the robot sees and flows may ask for any command kind.
///
/// One decide() is the engine's step order: (1) the current mode's guards, in the order the edges
/// were added, at time t + dt after the mode was held dt longer; (2) at most one transition with
/// its reset; (3) the (new) mode's flow is the command. The decision reports the mode and, when a
/// transition fired, its edge as the guard: the run's transition log (RunResult::transitions)
/// then names the guard (RunResult::guard_names[edge]) and counts towards chatter_episodes.
/// A terminal mode is STOP: its flow normally returns Command::goal_reached(), after which the
/// simulator resets the controller for the next goal (initial mode, initial memory).

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/nav/controller.hpp"

namespace floornav {

/// Runs a HybridAutomaton<Observation, Memory, Command>. The automaton is immutable and may be
/// shared by many robots (even across fleet threads: its guards, resets and flows must then not
/// touch shared mutable state); each controller has its own State.
template <class Memory>
class AutomatonController final : public Controller {
 public:
  using Automaton = HybridAutomaton<Observation, Memory, Command>;
  using State = typename Automaton::State;

  /// `initial_memory` is the memory every run (and every goal of a route) starts with.
  explicit AutomatonController(std::shared_ptr<const Automaton> automaton,
                               Memory initial_memory = {})
      : Controller(mode_names_of(*automaton), guard_names_of(*automaton)),
        automaton_(std::move(automaton)),
        initial_memory_(std::move(initial_memory)),
        state_(automaton_->initial_state(initial_memory_)) {}

  Decision decide(const Observation& obs) override {
    const auto transition = automaton_->step(obs, state_, obs.t + obs.dt, obs.dt);
    return {automaton_->flow(obs, state_), state_.mode, transition ? transition->edge : -1};
  }
  void reset() override { state_ = automaton_->initial_state(initial_memory_); }
  int mode() const override { return state_.mode; }

  const Automaton& automaton() const { return *automaton_; }
  /// The mode, time in mode, memory and the engine's own chatter monitor (its set_chatter_rule;
  /// the run's chatter_episodes use the controller section's chatter_switches/chatter_window).
  const State& state() const { return state_; }

 private:
  static std::vector<std::string> mode_names_of(const Automaton& a) {
    std::vector<std::string> names;
    for (const auto& m : a.modes()) names.push_back(m.name);
    return names;
  }
  static std::vector<std::string> guard_names_of(const Automaton& a) {
    std::vector<std::string> names;
    for (const auto& e : a.edges()) names.push_back(e.guard_name);
    return names;
  }

  std::shared_ptr<const Automaton> automaton_;
  Memory initial_memory_;
  State state_;
};

/// A factory for Scenario::set_controller or a robot's ControllerConfig: one automaton, shared,
/// and one AutomatonController (own state) per robot.
template <class Memory>
ControllerFactory make_automaton_controller(HybridAutomaton<Observation, Memory, Command> automaton,
                                            Memory initial_memory = {}) {
  auto shared =
      std::make_shared<const HybridAutomaton<Observation, Memory, Command>>(std::move(automaton));
  return [shared = std::move(shared), initial_memory = std::move(initial_memory)](
             const ControllerContext&) -> std::unique_ptr<Controller> {
    return std::make_unique<AutomatonController<Memory>>(shared, initial_memory);
  };
}

}  // namespace floornav
