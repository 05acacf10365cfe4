#include "floornav/nav/controller_registry.hpp"

#include <fmt/format.h>

#include <array>

#include "floornav/nav/dwa_controller.hpp"
#include "floornav/nav/navigation_controller.hpp"

namespace floornav {

namespace {

// The chapter's automata: one per kind and parameters, shared by the robots of a maker.
template <ControllerKind kKind>
std::unique_ptr<Controller> make_chapter(const ControllerConfig& config, const ControllerContext&,
                                         SharedAutomata& automata) {
  return std::make_unique<NavigationController>(automata.get(kKind, config.params), config.params);
}

std::unique_ptr<Controller> make_dwa(const ControllerConfig& config,
                                     const ControllerContext& context, SharedAutomata&) {
  return std::make_unique<DwaController>(config.params, config.dwa, context.robot);
}

// The work of a dwa step is bounded before the controller is made (its discs, its roll-outs): a
// sliver footprint or a fine roll-out of many samples is refused, not run.
std::optional<ControllerConfigProblem> check_dwa(const ControllerConfig& config,
                                                 const RobotSpec& robot) {
  const double discs = dwa_footprint_discs(robot.footprint);
  if (discs > kMaxDwaFootprintDiscs)
    return ControllerConfigProblem{
        true, "footprint",
        fmt::format("is {:.3g} times as long as it is wide: the dwa controller would cover it "
                    "with as many discs, more than the {} allowed",
                    discs, kMaxDwaFootprintDiscs)};
  const DwaParams& p = config.dwa;
  const double poses = dwa_roll_out_poses(p);
  const double checks = static_cast<double>(p.v_samples) * p.omega_samples * poses * discs;
  if (checks > kMaxDwaChecksPerStep)
    return ControllerConfigProblem{
        false, "dwa",
        fmt::format("v_samples x omega_samples x horizon / sim_step x footprint discs = "
                    "{} x {} x {:.6g} x {:.6g} = {:.3g} footprint checks a step, more than the "
                    "{:.0e} allowed: fewer samples, a shorter horizon or a longer sim_step",
                    p.v_samples, p.omega_samples, poses, discs, checks, kMaxDwaChecksPerStep)};
  return std::nullopt;
}

// Each chapter kind is named as ControllerKind's table names it (one spelling of each name).
constexpr std::string_view chapter_name(ControllerKind kind) {
  return to_string(kind);
}

const std::array<BuiltinController, 5> kBuiltins{{
    {chapter_name(ControllerKind::Hybrid),
     "the complete automaton of Fig 5.11: go-to-goal, follow-boundary cw/ccw, avoid-obstacle, "
     "stop",
     "", &make_chapter<ControllerKind::Hybrid>},
    {chapter_name(ControllerKind::HardSwitch),
     "go-to-goal <-> avoid-obstacle on the clearance vs d_o (Fig 5.7): can chatter (Fig 5.9)", "",
     &make_chapter<ControllerKind::HardSwitch>},
    {chapter_name(ControllerKind::Blended),
     "go-to-goal and avoid-obstacle blended by the clearance (eq. 5.21)", "",
     &make_chapter<ControllerKind::Blended>},
    {chapter_name(ControllerKind::GoToGoal),
     "go-to-goal alone (eqs. 5.16-5.19): hits whatever is in the way", "",
     &make_chapter<ControllerKind::GoToGoal>},
    {"dwa", "the dynamic window approach (Fox, Burgard, Thrun 1997), a baseline", "dwa", &make_dwa,
     &check_dwa},
}};

}  // namespace

std::span<const BuiltinController> builtin_controllers() {
  return kBuiltins;
}

const BuiltinController* find_builtin_controller(std::string_view name) {
  for (const BuiltinController& b : kBuiltins)
    if (b.name == name) return &b;
  return nullptr;
}

std::string builtin_controller_choices() {
  return list_choices(kBuiltins, [](const BuiltinController& b) { return b.name; });
}

}  // namespace floornav
