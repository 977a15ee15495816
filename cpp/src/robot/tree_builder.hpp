#pragma once
// Internal: appending bodies to a RobotTree, shared by the URDF loader and free_object().

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "robot/bodies.hpp"

namespace pathpace::detail {

/// Spatial inertia (angular first) about the body origin of mass m, centre of mass c and rotational
/// inertia Ic about c, all in body coordinates.
Matrix6 spatial_inertia(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& Ic);

Eigen::VectorXd as_vector(const std::vector<double>& v);

/// Throws InvalidInput unless gravity is finite and at most 1e3 m/s² (see tree_builder.cpp).
void check_gravity(const Eigen::Vector3d& g);

/// Appends bodies, joints and links to a model under construction; the limits wait in std::vectors
/// until store_limits.
struct TreeBuilder {
  std::vector<Body>& bodies;
  std::vector<std::string>& joint_names;
  std::vector<std::string>& link_names;
  std::map<std::string, std::pair<int, Eigen::Isometry3d>>& links;
  std::vector<double> q_lo{}, q_hi{}, v_max{}, effort{};

  /// A body of zero inertia behind a joint at `tree` (the joint frame in the parent's); returns its index.
  int add_body(int parent, RobotModel::JointType type, const Eigen::Vector3d& axis, const Eigen::Isometry3d& tree,
               const std::string& name, double lo, double hi, double vel, double eff);
  /// The six virtual joints of RobotModelOptions::floating_base (x, y, z, then rotations about z, y, x;
  /// unlimited, unactuated). Returns the last one's body, which carries the root link.
  int add_floating_base();
  /// A link carried by `body` at `placement` in that body's frame.
  void add_link(const std::string& name, int body, const Eigen::Isometry3d& placement);
  void store_limits(Eigen::VectorXd& lo, Eigen::VectorXd& hi, Eigen::VectorXd& vel, Eigen::VectorXd& eff) const;
};

}  // namespace pathpace::detail
