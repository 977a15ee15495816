#include "pathpace/robot_workspace.hpp"

#include "pathpace/robot_model.hpp"

namespace pathpace {

RobotWorkspace::RobotWorkspace(const RobotModel& model) {
  const size_t nb = model.bodies().size();
  E.resize(nb);
  r.resize(nb);
  v.resize(nb);
  a.resize(nb);
  f.resize(nb);
  S.resize(nb);
  tmp.setZero(model.nq());
  zero.setZero(model.nq());
}

}  // namespace pathpace
