#include "pathpace/robot_workspace.hpp"

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

// A moved-from workspace (scratch_ null) copies as one; a model call with it is undefined.
RobotWorkspace::RobotWorkspace(const RobotWorkspace& other)
    : scratch_(other.scratch_ ? std::make_unique<detail::RobotScratch>(*other.scratch_) : nullptr) {}
RobotWorkspace::RobotWorkspace(RobotWorkspace&& other) noexcept = default;
RobotWorkspace& RobotWorkspace::operator=(const RobotWorkspace& other) {
  if (this != &other) scratch_ = other.scratch_ ? std::make_unique<detail::RobotScratch>(*other.scratch_) : nullptr;
  return *this;
}
RobotWorkspace& RobotWorkspace::operator=(RobotWorkspace&& other) noexcept = default;
RobotWorkspace::~RobotWorkspace() = default;

}  // namespace pathpace
