#pragma once
/// @file
/// The built-in controller kinds, by name: what `controller.kind` may say. Each entry makes its
/// controller, names the section its own parameters sit in, says in a line what it is (the
/// reader's messages and the key-table test use it), and may refuse a configuration whose work
/// per step would be unbounded. Adding a kind is adding an entry: the scenario reader, the
/// ControllerMaker and validate_scenario look names up here and nowhere else.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "floornav/nav/controller.hpp"

namespace floornav {

class SharedAutomata;

/// A configuration a kind refuses, and where: a key of the robot (`footprint`) or of the
/// controller section (`dwa`).
struct ControllerConfigProblem {
  bool robot_key{false};  ///< `key` is in the robot section, not the controller's
  std::string key;
  std::string what;
};

struct BuiltinController {
  std::string_view name;  ///< the `controller.kind` that selects it
  std::string_view summary;
  /// Where its own parameters sit in the controller section: "" for the chapter's keys at the
  /// section's top level (NavigationParams), else the sub-section (`dwa`: DwaParams).
  std::string_view params_section;
  /// Makes the controller of one robot; robots of a maker share what `automata` holds.
  std::unique_ptr<Controller> (*make)(const ControllerConfig& config,
                                      const ControllerContext& context, SharedAutomata& automata);
  /// The configuration's problem for this kind, if any (nullptr: it has none to check).
  std::optional<ControllerConfigProblem> (*check)(const ControllerConfig& config,
                                                  const RobotSpec& robot){nullptr};
};

/// Every built-in kind, in the order the docs list them.
std::span<const BuiltinController> builtin_controllers();
/// The kind called `name`, or nullptr.
const BuiltinController* find_builtin_controller(std::string_view name);
/// "hybrid, hard_switch, ... or dwa", for messages.
std::string builtin_controller_choices();

}  // namespace floornav
