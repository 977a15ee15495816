#pragma once
/// @file robot_model.hpp
/// A rigid-body tree from a URDF, immutable after loading, with our own Eigen dynamics (RNEA).

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pathpace {

class RobotWorkspace;

namespace detail {
struct RobotTree;       // the bodies and the link map (cpp/src/robot/bodies.hpp, never installed)
struct MimicMap;        // mimic joints' coordinate map (cpp/src/robot/bodies.hpp)
struct RobotInternals;  // how cpp/src/robot's algorithms reach both (cpp/src/robot/bodies.hpp)
}  // namespace detail

/// Options of RobotModel::from_urdf_file / from_urdf_string.
struct RobotModelOptions {
  /// Six virtual joints in front of the root link: translations along world x, y, z, then rotations
  /// about z, y, x (the paper's "6 generalized coordinates"), so the root pose is
  /// Trans(x, y, z) · Rz(a) · Ry(b) · Rx(c). They come first in q, have no velocity or acceleration
  /// limit and zero effort (unactuated). Names: "floating_x", "floating_y", "floating_z",
  /// "floating_rz", "floating_ry", "floating_rx".
  bool floating_base = false;
  /// Joints held at a value and removed from q (e.g. gripper fingers). A mimic joint whose joint is
  /// locked is held at multiplier · value + offset.
  std::map<std::string, double> locked_joints;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
};

/// The kinematic tree: one body per movable joint (fixed joints merged into their parent, inertias
/// combined), in depth-first order from the root with children in urdfdom's order, which is also
/// pinocchio's. Immutable and shareable across threads; scratch space lives in RobotWorkspace.
///
/// Mimic joints (URDF <mimic>, e.g. the second finger of a gripper) have a body but no coordinate:
/// q_mimic = multiplier · q_joint + offset, as in pinocchio. q, q̇, q̈ and τ are then over the other
/// joints only (nq is less than the number of bodies); the mimic joint's torque acts on its joint scaled
/// by the multiplier (τ = Eᵀ τ_bodies by virtual work, E = ∂q_bodies/∂q), and its own effort limit is not
/// used.
class RobotModel {
 public:
  enum class JointType { Revolute, Prismatic };

  /// An empty model (no bodies, nq = 0); models come from the factories below.
  RobotModel();

  static RobotModel from_urdf_file(const std::string& path, const RobotModelOptions& options = {});
  static RobotModel from_urdf_string(const std::string& xml, const RobotModelOptions& options = {});

  /// One model of several independent trees (robots and free objects, sec. III.b): q is the parts'
  /// coordinates in order. Link names must be unique across the parts (contacts refer to links); a
  /// joint name that occurs in more than one part is qualified as "<part name>/<joint>" (e.g. the
  /// floating_* coordinates of two floating parts). Gravity must agree.
  static RobotModel combine(const std::vector<RobotModel>& parts, const std::string& name = "");

  /// A free rigid body (sec. III.b): one link `name` with six floating coordinates (see
  /// RobotModelOptions::floating_base) and zero effort. `com` and `inertia` (about the centre of mass,
  /// symmetric positive semi-definite) are in the link frame.
  static RobotModel free_object(const std::string& name, double mass, const Eigen::Vector3d& com = Eigen::Vector3d::Zero(),
                                const Eigen::Matrix3d& inertia = Eigen::Matrix3d::Zero(),
                                const Eigen::Vector3d& gravity = Eigen::Vector3d(0.0, 0.0, -9.81));

  int nq() const { return static_cast<int>(joint_names_.size()); }
  const std::string& name() const { return name_; }
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  const std::vector<std::string>& link_names() const { return link_names_; }
  const Eigen::VectorXd& lower_position_limits() const { return q_lo_; }
  const Eigen::VectorXd& upper_position_limits() const { return q_hi_; }
  const Eigen::VectorXd& velocity_limits() const { return v_max_; }
  const Eigen::VectorXd& effort_limits() const { return effort_; }
  const Eigen::Vector3d& gravity() const { return gravity_; }
  /// The same as gravity(): Python's name (where gravity(q) is the torque vector), usable in both.
  const Eigen::Vector3d& gravity_vector() const { return gravity_; }

  /// τ = M(q) q̈ + C(q, q̇) q̇ + g(q) by the recursive Newton-Euler algorithm.
  Eigen::VectorXd inverse_dynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) const;
  void inverse_dynamics(RobotWorkspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                        const Eigen::Ref<const Eigen::VectorXd>& qd, const Eigen::Ref<const Eigen::VectorXd>& qdd,
                        bool with_gravity, Eigen::Ref<Eigen::VectorXd> tau) const;
  Eigen::MatrixXd mass_matrix(const Eigen::VectorXd& q) const;
  Eigen::VectorXd gravity_torques(const Eigen::VectorXd& q) const;

  /// The torque coefficients of eq. (12) on a path: τ = a·ṡ² + b·s̈ + c with a = M p'' + C(q, p') p',
  /// b = M p', c = g(q), at q = p(s).
  void path_torque_coefficients(RobotWorkspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                                const Eigen::Ref<const Eigen::VectorXd>& dq, const Eigen::Ref<const Eigen::VectorXd>& ddq,
                                Eigen::Ref<Eigen::VectorXd> a, Eigen::Ref<Eigen::VectorXd> b,
                                Eigen::Ref<Eigen::VectorXd> c) const;

  /// The same at many samples: row s of q, dq, ddq (each (samples, nq)) gives row s of a, b, c. Where the
  /// compiler has vector types (GCC, Clang), each sweep takes as many samples as the CPU has SIMD lanes
  /// for doubles (x86-64: 2 with SSE2, 4 with AVX2 + FMA, 8 with AVX-512; chosen at run time).
  void path_torque_coefficients_batch(RobotWorkspace& ws, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                      const Eigen::MatrixXd& ddq, Eigen::MatrixXd& a, Eigen::MatrixXd& b,
                                      Eigen::MatrixXd& c) const;

  /// Centre of mass of the whole model at q, in world coordinates (m). Links fixed to the world (a
  /// fixed base's root link) do not move and are not counted, as in pinocchio's centerOfMass.
  Eigen::Vector3d center_of_mass(const Eigen::VectorXd& q) const;
  /// Total mass of the moving bodies (kg), the weight of center_of_mass().
  double mass() const;

  /// How this model was built, so that an identical one can be built elsewhere (Python pickling,
  /// another process or machine): the URDF text and options, the parts of combine() with its name, or
  /// free_object()'s arguments. rebuild(source()) gives an identical model.
  struct Source {
    enum class Kind { Urdf, Combine, FreeObject };
    Kind kind = Kind::Urdf;
    std::string urdf;                 ///< Urdf: the XML text
    RobotModelOptions options;        ///< Urdf: the options; FreeObject: options.gravity
    std::vector<RobotModel> parts;    ///< Combine
    std::string name;                 ///< Combine, FreeObject
    double mass = 0.0;                ///< FreeObject
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  };
  const Source& source() const { return *source_; }
  static RobotModel rebuild(const Source& source);

  /// World placement of a link's frame (4x4 homogeneous).
  Eigen::Matrix4d frame_placement(const Eigen::VectorXd& q, const std::string& link) const;
  /// World-frame linear Jacobian (3 x nq) of a point fixed in a link (coordinates in the link frame).
  Eigen::MatrixXd point_jacobian(const Eigen::VectorXd& q, const std::string& link, const Eigen::Vector3d& point) const;

  /// World-frame Jacobian (6 x nq) of a point fixed in a link (coordinates in the link frame): rows 0-2 the
  /// point's linear velocity, rows 3-5 the link's angular velocity (pinocchio's LOCAL_WORLD_ALIGNED order).
  Eigen::MatrixXd frame_jacobian(const Eigen::VectorXd& q, const std::string& link, const Eigen::Vector3d& point) const;

  /// A point fixed in a link on a path q = p(s), per sample (row k of each matrix; see path_frame_motion).
  struct FrameMotion {
    Eigen::MatrixXd rotation;              ///< (samples, 9): the link frame's world rotation R, column-major
    Eigen::MatrixXd velocity;              ///< (samples, 3): J p', the point's world velocity at ṡ = 1
    Eigen::MatrixXd angular_velocity;      ///< (samples, 3): J_ω p', the link's angular velocity at ṡ = 1
    Eigen::MatrixXd acceleration;          ///< (samples, 3): J p'' + J̇(p') p', the point's classical acceleration at ṡ = 1, s̈ = 0
    Eigen::MatrixXd angular_acceleration;  ///< (samples, 3): J_ω p'' + J̇_ω(p') p'
  };
  /// The motion of `point` (link coordinates) on `link` at samples q = p(s), dq = p', ddq = p'' (each
  /// (samples, nq)), by one forward pass per sample, no Jacobian formed: since q̇ = p' ṡ and
  /// q̈ = p' s̈ + p'' ṡ² (eq. 10-11), the point's velocity is velocity·ṡ and its acceleration
  /// acceleration·ṡ² + velocity·s̈, exactly (likewise the angular ones). The J̇ q̇ terms are the classical
  /// (not spatial) ones: the second derivative of the world position.
  FrameMotion path_frame_motion(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq,
                                const std::string& link, const Eigen::Vector3d& point) const;

  /// A mimic joint: q[name] = multiplier · q[joint] + offset.
  struct MimicJoint {
    std::string name, joint;
    double multiplier = 1.0, offset = 0.0;
  };
  const std::vector<MimicJoint>& mimic_joints() const;
  /// Mimic joints locked without their joint (RobotModelOptions::locked_joints): each is frozen at its
  /// value while its joint moves, its relation dropped (as a model reduced on that joint alone, e.g.
  /// pinocchio's buildReducedModel). Locking its joint instead keeps the relation. A mimic locked with its
  /// joint at values that break the relation is an InvalidInput.
  const std::vector<std::string>& frozen_mimic_joints() const { return frozen_mimics_; }
  /// The kind of each coordinate q[j] (nq entries): Revolute (rad) or Prismatic (m); a floating base's
  /// x, y, z are prismatic, its rotations revolute.
  std::vector<JointType> joint_types() const;

  /// Body index of a link (merged links map to the body that carries them) and the link's fixed
  /// placement in that body's frame. Throws InvalidInput for an unknown name.
  int body_of_link(const std::string& link, Eigen::Isometry3d& in_body) const;

  /// World poses of every body at q (one pass), for callers that need several frames or
  /// Jacobians at the same configuration; no argument checks.
  void body_placements(const Eigen::Ref<const Eigen::VectorXd>& q, std::vector<Eigen::Isometry3d>& T) const;
  /// Adds `sign` times the world-frame linear Jacobian of the world point `p` moving with body `body`
  /// to J (3 x nq), given the body poses T from body_placements(). Nothing for body -1 (the world). A
  /// mimic body's column goes to its joint's, times the multiplier.
  void add_point_jacobian(const std::vector<Eigen::Isometry3d>& T, int body, const Eigen::Vector3d& p, double sign,
                          Eigen::Ref<Eigen::MatrixXd> J) const;

 private:
  friend struct detail::RobotInternals;
  void check_q(const Eigen::Ref<const Eigen::VectorXd>& v, const char* name) const;
  // After loading with one coordinate per body: make the mimic bodies follow their joints.
  void remove_mimic_coordinates(const std::vector<MimicJoint>& mimics);
  std::string name_;
  // Immutable once built, so copies share it (and the model stays safe to share across threads).
  std::shared_ptr<const detail::RobotTree> tree_;
  std::vector<std::string> joint_names_, link_names_;
  Eigen::VectorXd q_lo_, q_hi_, v_max_, effort_;
  Eigen::Vector3d gravity_;
  std::shared_ptr<const Source> source_;
  std::shared_ptr<const detail::MimicMap> mimic_;  // null without mimic joints
  std::vector<std::string> frozen_mimics_;
};

}  // namespace pathpace
