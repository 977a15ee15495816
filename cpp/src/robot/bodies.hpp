#pragma once
// Internal: what RobotModel and RobotWorkspace hold behind their opaque pointers, shared by the files
// of cpp/src/robot (the loader and combine() build it, rnea, torque_lanes and kinematics read it).

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "pathpace/robot_model.hpp"
#include "pathpace/robot_workspace.hpp"

namespace pathpace::detail {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// One movable joint and the rigid body it carries (fixed joints merged into it). Body i moves with
/// coordinate i of the model with one coordinate per body (with mimic joints: MimicMap::bodies_model).
struct Body {
  int parent = -1;  // body index, -1 for the world
  RobotModel::JointType type = RobotModel::JointType::Revolute;
  Eigen::Vector3d axis;    // joint axis in the joint (= body) frame
  int axis_index = -1;     // u if axis is the coordinate axis e_u exactly (most URDF joints), else -1
  Eigen::Matrix3d E_tree;  // Featherstone: parent coordinates -> joint frame, rotation
  Eigen::Vector3d r_tree;  //   and origin of the joint frame in parent coordinates
  Matrix6 inertia;         // spatial inertia in body coordinates (angular first)
};

/// The kinematic tree in depth-first order (a parent before its children).
struct RobotTree {
  std::vector<Body> bodies;
  std::map<std::string, std::pair<int, Eigen::Isometry3d>> links;  // link -> (body, placement in body)
};

/// Mimic joints: the dynamics run on the same tree with one coordinate per body (bodies_model), with
/// q_bodies = E q + o on the way in and τ = Eᵀ τ_bodies on the way out (virtual work).
struct MimicMap {
  std::vector<RobotModel::MimicJoint> joints;
  std::shared_ptr<const RobotModel> bodies_model;
  Eigen::MatrixXd E;  // (bodies, nq): ∂q_bodies/∂q
  Eigen::VectorXd o;  // (bodies): offsets
};

/// RobotWorkspace's buffers, one entry per body.
struct RobotScratch {
  std::vector<Eigen::Matrix3d> E;  // body i: rotation parent -> body coordinates
  std::vector<Eigen::Vector3d> r;  // body i: its origin in parent coordinates
  std::vector<Vector6> v, a, f;    // spatial velocity, acceleration, force (body coordinates)
  std::vector<Vector6> S;          // joint motion subspace
  std::vector<unsigned char> abc;  // the torque sweep's per-body records (torque_lanes.cpp: abc_bodies)
  Eigen::VectorXd qd;              // the RNEA's q̇ (rnea.cpp)
};

/// The one door from cpp/src/robot into the private parts of RobotModel and RobotWorkspace.
struct RobotInternals {
  static const std::vector<Body>& bodies(const RobotModel& model) { return model.tree_->bodies; }
  static const MimicMap* mimic(const RobotModel& model) { return model.mimic_.get(); }
  /// The workspace's buffers, checked against the model they are used with: a moved-from workspace, or one
  /// made for a model with another number of bodies, would otherwise be read out of bounds.
  static RobotScratch& scratch(RobotWorkspace& ws, const RobotModel& model);
};

}  // namespace pathpace::detail
