#include "pathpace/result.hpp"

#include "pathpace/errors.hpp"
#include "pathpace/trajectory.hpp"

namespace pathpace {

const char* to_string(Status status) {
  switch (status) {
    case Status::Optimal: return "optimal";
    case Status::Infeasible: return "infeasible";
    case Status::IterationLimit: return "iteration_limit";
    case Status::NumericalError: return "numerical_error";
    case Status::Unbounded: return "unbounded";
    case Status::TimeLimit: return "time_limit";
  }
  return "unknown";
}

Trajectory Result::trajectory() const {
  if (!ok() || sdot.size() < 2 || !path)
    throw Error(std::string("no trajectory: the solve ended with status ") + to_string(status) +
                (message.empty() ? "" : " (" + message + ")"));
  Trajectory t = sddot_points.size() ? Trajectory(path, s, sdot, sddot_points) : Trajectory(path, s, sdot);
  t.set_robot(robot);
  t.set_contacts(contacts);
  t.set_contact_phases(contact_phases);
  return t;
}

}  // namespace pathpace
