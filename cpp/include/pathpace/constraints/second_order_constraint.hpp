#pragma once
/// @file second_order_constraint.hpp
/// A constraint F(q) w <= g(q) on w = A(q) q̈ + q̇ᵀB(q) q̇ + f(q), with w from the user's inverse dynamics
/// (toppra's second-order form); torque limits from the user's dynamics are its case F = [I; -I].

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"

namespace pathpace {

/// The user's functions of a SecondOrderConstraint, vectorised over samples: row i of each argument is one
/// sample, so one call evaluates a whole batch (a callback per sample would cost more than the solve).
struct SecondOrderFunctions {
  /// w = id(q, q̇, q̈) for m samples: q, qd, qdd of shape (m, n); returns W of shape (m, nw).
  using InverseDynamics =
      std::function<Eigen::MatrixXd(const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd, const Eigen::MatrixXd& qdd)>;
  /// A function of q (m, n): F returns the m matrices F(q_i) (r, nw) stacked, shape (m·r, nw) (rows i·r to
  /// i·r + r - 1 are sample i); g returns shape (m, r), g(q_i) in row i.
  using OfQ = std::function<Eigen::MatrixXd(const Eigen::MatrixXd& q)>;

  SecondOrderFunctions() = default;
  SecondOrderFunctions(const SecondOrderFunctions&) = default;
  SecondOrderFunctions& operator=(const SecondOrderFunctions&) = default;
  virtual ~SecondOrderFunctions() = default;

  InverseDynamics inverse_dynamics;
  OfQ F;                       ///< empty: F_constant at every sample
  OfQ g;                       ///< empty: g_constant at every sample
  Eigen::MatrixXd F_constant;  ///< (r, nw), used when F is empty
  Eigen::VectorXd g_constant;  ///< (r,), used when g is empty; +inf entries are absent limits
};

/// What names a SecondOrderConstraint and its rows.
struct SecondOrderOptions {
  std::string name = "second-order constraint";  ///< name() and the prefix of the default row labels
  std::vector<std::string> labels;                ///< one per row of F (r); empty: "<name> row j"
  std::string family = "second order";            ///< relaxation() widens g (see relaxed); empty: not relaxed
};

/// F(q) w <= g(q) with w = id(q, q̇, q̈). At a grid point, q = p, q̇ = p' ṡ, q̈ = p' s̈ + p'' ṡ² (eq. 10-11)
/// make w affine in (x, u) = (ṡ², s̈) because id is quadratic in q̇ and linear in q̈ (eq. 12): with
///   c = id(p, 0, 0),  b_w = id(p, 0, p') - c,  a_w = id(p, p', p'') - c
/// w = a_w x + b_w u + c, and the rows are (F a_w) x + (F b_w) u <= g - F c. All 3(N+1) evaluations of id
/// are one call; F and g are called once each with the N+1 samples of q.
///
/// The functions must be safe to call from any thread (solve() and guarantee = continuous's audit
/// evaluate the rows again, on new samples, while solving). What they return is checked at each call:
/// shapes, W and F finite, g a number or +inf; an InvalidInput names the function, the sample and s.
class SecondOrderConstraint : public Constraint {
 public:
  using Options = SecondOrderOptions;

  /// `functions` with inverse_dynamics set, F or F_constant, g or g_constant (a constant F or g is
  /// checked here: shapes and entries).
  SecondOrderConstraint(std::shared_ptr<const SecondOrderFunctions> functions, Options options);

  /// Convenience: std::functions of q for F and g.
  SecondOrderConstraint(SecondOrderFunctions::InverseDynamics inverse_dynamics, SecondOrderFunctions::OfQ F,
                        SecondOrderFunctions::OfQ g, SecondOrderOptions options = SecondOrderOptions());

  /// Torque limits tau_min <= id(q, q̇, q̈) <= tau_max (eq. 15) from the user's inverse dynamics: F and g
  /// constant, row 2j = τ_j <= tau_max[j], row 2j+1 = -τ_j <= -tau_min[j] (TorqueLimits' rows, in its
  /// order); the limits are scale·[tau_min, tau_max] shrunk by `margin` on each side, as TorqueLimits'.
  /// Family "torque", labels "torque <joint> upper/lower" with the problem's joint names ("joint j"
  /// without). `functions` needs only inverse_dynamics (F, g are replaced).
  static std::shared_ptr<const SecondOrderConstraint> torque_limits(
      std::shared_ptr<const SecondOrderFunctions> functions, const Eigen::VectorXd& tau_min,
      const Eigen::VectorXd& tau_max, double scale = 1.0, double margin = 0.0,
      std::vector<std::string> joint_names = {});
  static std::shared_ptr<const SecondOrderConstraint> torque_limits(SecondOrderFunctions::InverseDynamics inverse_dynamics,
                                                                    const Eigen::VectorXd& tau_min,
                                                                    const Eigen::VectorXd& tau_max, double scale = 1.0,
                                                                    double margin = 0.0);

  std::string name() const override { return options_.name; }
  ConstraintRows evaluate(const PathSamples& samples) const override;
  std::string family() const override { return options_.family; }
  /// g widened by `scale` about zero row by row (widen_upper: g >= 0 becomes scale·g, g < 0 becomes g /
  /// scale), so the feasible set grows with the scale; for torque limits this is TorqueLimits::relaxed.
  std::shared_ptr<const Constraint> relaxed(double scale) const override;
  /// Torque limits without joint names take the problem's (Constraint::with_joint_names); nullptr otherwise.
  std::shared_ptr<const Constraint> with_joint_names(const std::vector<std::string>& names) const override;

  /// The functions object the constraint was made from (for torque_limits, the one given to it; its own F
  /// and g are the constant rows of eq. 15). A binding keeps its callables there (pickling).
  const std::shared_ptr<const SecondOrderFunctions>& functions() const { return user_functions_; }
  const Options& options() const { return options_; }
  /// The relaxation scale applied to g so far (1 unless made by relaxed()).
  double g_scale() const { return g_scale_; }
  /// The same constraint with g widened by `scale` (>= 1) as relaxed() does, for a general (not torque)
  /// constraint; what relaxed() returns for it, and what unpickling a relaxed one rebuilds.
  std::shared_ptr<const SecondOrderConstraint> with_g_scale(double scale) const;
  /// True for torque_limits(); then tau_min/tau_max (after scale and margin) and joint_names are set.
  bool is_torque_limits() const { return torque_; }
  const Eigen::VectorXd& tau_min() const { return tau_min_; }
  const Eigen::VectorXd& tau_max() const { return tau_max_; }
  const std::vector<std::string>& joint_names() const { return joint_names_; }

 private:
  std::shared_ptr<const SecondOrderFunctions> functions_;       // what evaluate() calls
  std::shared_ptr<const SecondOrderFunctions> user_functions_;  // what the user gave (functions())
  Options options_;
  double g_scale_ = 1.0;
  bool torque_ = false;
  Eigen::VectorXd tau_min_, tau_max_;
  std::vector<std::string> joint_names_;

  Eigen::Index constant_rows() const;  // r when F is constant, -1 otherwise
  std::vector<std::string> row_labels(Eigen::Index r) const;
};

}  // namespace pathpace
