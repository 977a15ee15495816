#pragma once
/// @file robot_workspace.hpp
/// Scratch space for RobotModel's algorithms: one per thread, reused across calls (pinocchio's Data).

#include <memory>

namespace pathpace {

class RobotModel;

namespace detail {
struct RobotScratch;    // the buffers themselves (cpp/src/robot/bodies.hpp, never installed)
struct RobotInternals;  // cpp/src/robot/bodies.hpp
}  // namespace detail

/// Made for one model (pass the workspace to that model's calls); a copy has buffers of its own. Not for
/// two threads at once: the model is shared, each thread holds its own workspace.
class RobotWorkspace {
 public:
  explicit RobotWorkspace(const RobotModel& model);
  RobotWorkspace(const RobotWorkspace& other);
  RobotWorkspace(RobotWorkspace&& other) noexcept;
  RobotWorkspace& operator=(const RobotWorkspace& other);
  RobotWorkspace& operator=(RobotWorkspace&& other) noexcept;
  ~RobotWorkspace();

 private:
  friend struct detail::RobotInternals;
  std::unique_ptr<detail::RobotScratch> scratch_;
};

}  // namespace pathpace
