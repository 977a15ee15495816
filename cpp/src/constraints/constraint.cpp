#include "pathpace/constraints/constraint.hpp"

#include "pathpace/errors.hpp"

namespace pathpace {

// The hooks a constraint only gets asked after saying yes to another one (can_absorb, per_grid_point,
// projected): reaching a default is a bug of the subclass, not bad input.
std::shared_ptr<const Constraint> Constraint::absorb(const Constraint& other) const {
  throw Error("constraint '" + name() + "' cannot absorb '" + other.name() + "' (can_absorb is false)");
}

std::shared_ptr<const Constraint> Constraint::at_grid_points(const std::vector<Eigen::Index>& /*kept*/) const {
  throw Error("constraint '" + name() + "' is not given per grid point (per_grid_point is false)");
}

int Constraint::slice(const PathSamples& /*samples*/, const Eigen::VectorXd& /*u*/, Eigen::VectorXd& /*x_lo*/,
                      Eigen::VectorXd& /*x_hi*/, const Eigen::VectorXd* /*x*/, SliceEdges* /*edges*/,
                      SliceStarts* /*starts*/) const {
  throw Error("constraint '" + name() + "' is not a projection (projected is false)");
}

}  // namespace pathpace
