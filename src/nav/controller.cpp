#include "floornav/nav/controller.hpp"

#include <cmath>
#include <utility>

namespace floornav {

bool Command::is_finite() const {
  return std::isfinite(a_) && std::isfinite(b_);
}

Controller::Controller(std::vector<std::string> mode_names, std::vector<std::string> guard_names)
    : mode_names_(std::move(mode_names)), guard_names_(std::move(guard_names)) {
  if (mode_names_.empty()) mode_names_.push_back("drive");
}

namespace {
class FunctionController final : public Controller {
 public:
  FunctionController(std::function<Command(const Observation&)> decide, std::string mode)
      : Controller({std::move(mode)}), decide_(std::move(decide)) {}
  Decision decide(const Observation& obs) override { return decide_(obs); }

 private:
  std::function<Command(const Observation&)> decide_;
};
}  // namespace

ControllerFactory make_controller(std::function<Command(const Observation&)> decide,
                                  std::string mode_name) {
  return [decide = std::move(decide), mode_name = std::move(mode_name)](
             const ControllerContext&) -> std::unique_ptr<Controller> {
    return std::make_unique<FunctionController>(decide, mode_name);
  };
}

}  // namespace floornav
