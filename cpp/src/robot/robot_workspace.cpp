#include "pathpace/robot_workspace.hpp"

#include <string>

#include "base/validate.hpp"
#include "robot/bodies.hpp"

namespace pathpace {

RobotWorkspace::RobotWorkspace(const RobotModel& model) : scratch_(std::make_unique<detail::RobotScratch>()) {
  const size_t nb = detail::RobotInternals::bodies(model).size();
  scratch_->E.resize(nb);
  scratch_->r.resize(nb);
  scratch_->v.resize(nb);
  scratch_->a.resize(nb);
  scratch_->f.resize(nb);
  scratch_->S.resize(nb);
  scratch_->qd.setZero(model.nq());
}

// A moved-from workspace (scratch_ null) copies as one; a model call with it throws (RobotInternals::scratch).
RobotWorkspace::RobotWorkspace(const RobotWorkspace& other)
    : scratch_(other.scratch_ ? std::make_unique<detail::RobotScratch>(*other.scratch_) : nullptr) {}
RobotWorkspace::RobotWorkspace(RobotWorkspace&& other) noexcept = default;
RobotWorkspace& RobotWorkspace::operator=(const RobotWorkspace& other) {
  if (this != &other) scratch_ = other.scratch_ ? std::make_unique<detail::RobotScratch>(*other.scratch_) : nullptr;
  return *this;
}
RobotWorkspace& RobotWorkspace::operator=(RobotWorkspace&& other) noexcept = default;
RobotWorkspace::~RobotWorkspace() = default;

detail::RobotScratch& detail::RobotInternals::scratch(RobotWorkspace& ws, const RobotModel& model) {
  const size_t nb = bodies(model).size();
  if (!ws.scratch_) fail("workspace: it was moved from; make one with RobotWorkspace(model)");
  if (ws.scratch_->E.size() != nb)
    fail("workspace: made for a model with " + std::to_string(ws.scratch_->E.size()) + " bodies, robot '" +
         model.name() + "' has " + std::to_string(nb) + "; make one with RobotWorkspace(model)");
  return *ws.scratch_;
}

}  // namespace pathpace
