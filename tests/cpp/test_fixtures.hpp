#pragma once
// Problems shared by the C++ tests of the projection, the contact constraint and the GLPK guard
// (header-only): a polytope with a known shadow, and a box carried on a sliding platform.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "lp/projection.hpp"
#include "pathpace/pathpace.hpp"

namespace pathpace::test {

// The projection's support function in direction (dx, du): the largest dx x + du u over its vertices.
inline double support(const detail::Projection& p, double dx, double du) {
  double best = -INFINITY;
  for (const detail::Vertex& v : p.vertices) best = std::max(best, dx * v.x + du * v.y);
  return best;
}

// |x| + |u| + |y| <= 1 as its 8 facets; its shadow on (x, u) is the diamond |x| + |u| <= 1.
inline detail::PolytopeLp octahedron() {
  detail::PolytopeLp lp;
  lp.A.resize(8, 3);
  int r = 0;
  for (int sx : {-1, 1})
    for (int su : {-1, 1})
      for (int sy : {-1, 1}) lp.A.row(r++) << sx, su, sy;
  lp.row_lo = Eigen::VectorXd::Constant(8, -INFINITY);
  lp.row_hi = Eigen::VectorXd::Ones(8);
  lp.col_lo = Eigen::VectorXd::Constant(3, -INFINITY);
  lp.col_hi = Eigen::VectorXd::Constant(3, INFINITY);
  return lp;
}

// One row over (x, u): row_lo <= a_x x + a_u u <= row_hi, x and u within their bounds (the small LPs of
// the dense simplex's and the slices' tests).
inline detail::PolytopeLp one_row_lp(double a_x, double a_u, double row_lo, double row_hi, const Eigen::Vector2d& col_lo,
                                     const Eigen::Vector2d& col_hi) {
  detail::PolytopeLp lp;
  lp.A.resize(1, 2);
  lp.A << a_x, a_u;
  lp.row_lo = Eigen::VectorXd::Constant(1, row_lo);
  lp.row_hi = Eigen::VectorXd::Constant(1, row_hi);
  lp.col_lo = col_lo;
  lp.col_hi = col_hi;
  return lp;
}

// y = 1e-8 u (row 0), 100 <= y <= 200, 0 <= x <= 1 (row 1: x <= 1): the shadow [0, 1] x [1e10, 2e10] lies
// beyond the stand-in bounds |u| <= 1e6, so the projection takes its other branch (a feasibility LP, grown
// bounds, rescaled columns).
inline detail::PolytopeLp beyond_stand_in() {
  detail::PolytopeLp lp;
  lp.A.resize(2, 3);
  lp.A.row(0) << 0, 1e-8, -1;
  lp.A.row(1) << 1, 0, 0;
  lp.row_lo = Eigen::Vector2d(0, -INFINITY);
  lp.row_hi = Eigen::Vector2d(0, 1);
  lp.col_lo = Eigen::Vector3d(0, -1e6, 100);
  lp.col_hi = Eigen::Vector3d(1e6, 1e6, 200);
  lp.stand_in = 1e6;
  return lp;
}

inline const char* kLifter = R"(<robot name="lifter">
 <link name="base"/>
 <link name="platform"><inertial><mass value="3"/><inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <joint name="slide" type="prismatic"><parent link="base"/><child link="platform"/><axis xyz="1 0 0"/><limit lower="-10" upper="10" velocity="100" effort="1000"/></joint>
</robot>)";

// A 3 kg platform on a prismatic joint carrying a free 2 kg box (sec. IV.E's pushing example).
inline std::shared_ptr<RobotModel> lifter_with_box() {
  const RobotModel lifter = RobotModel::from_urdf_string(kLifter);
  const RobotModel box = RobotModel::free_object("box", 2.0, Eigen::Vector3d(0, 0, 0.05), 0.01 * Eigen::Matrix3d::Identity());
  return std::make_shared<RobotModel>(RobotModel::combine({lifter, box}));
}

// The contact options of the box on the platform in most tests: 4-edge pyramids, a minimum normal force (N).
inline ContactOptions box_options(double min_normal_force = 0.0) {
  ContactOptions opt;
  opt.cone_edges = 4;
  opt.min_normal_force = min_normal_force;
  return opt;
}

// The box's four bottom corners on the platform, friction mu.
inline std::vector<Contact> corners(double mu) {
  std::vector<Contact> out;
  for (double x : {-0.1, 0.1})
    for (double y : {-0.1, 0.1}) {
      Contact c;
      c.link = "box";
      c.other_link = "platform";
      c.point = Eigen::Vector3d(x, y, 0.0);
      c.friction = mu;
      out.push_back(c);
    }
  return out;
}

}  // namespace pathpace::test
