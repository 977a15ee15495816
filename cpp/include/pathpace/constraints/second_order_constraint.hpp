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

// docstrings.txt @@ SecondOrderConstraint
/// @brief F(q) w <= g(q) with w = inverse_dynamics(q, q̇, q̈): toppra's second-order constraint (friction cones,
/// an object held by a gripper, a tray that must not slip, torque limits).
///
/// w = A(q) q̈ + q̇ᵀB(q) q̇ + f(q) is quadratic in q̇ and linear in q̈, so on the path (q = p, q̇ = p' ṡ,
/// q̈ = p' s̈ + p'' ṡ², eq. 10-12) three evaluations per grid point give w = a ṡ² + b s̈ + c:
/// c = id(p, 0, 0), b = id(p, 0, p') - c, a = id(p, p', p'') - c; the rows are (F a) ṡ² + (F b) s̈ <= g - F c.
/// All 3(N+1) evaluations are one call of inverse_dynamics, and F and g are called once each with the N+1
/// samples of q: vectorise them (numpy), since a call per sample costs more than the solve.
///
/// The callables are called from the solver's threads (the GIL taken for each call), again during
/// `solve(guarantee='continuous')`, whose audit samples the rows between grid points, and on a restart or
/// a contact switch (new grid points). What they return is checked (shapes, finite w and F, g a number or
/// +inf): InvalidInput names the callable, the grid point and s. An exception they raise comes out of
/// the pathpace call as it was. The constraint pickles when its callables do (module-level functions, or
/// objects with `__reduce__`); pickle.PicklingError names the one that does not.
///
/// Differences from toppra's `SecondOrderConstraint(inv_dyn, constraint_F, constraint_g, dof)`: the same
/// order and meaning of the first three arguments, but vectorised (`vectorized=False` takes toppra's
/// per-sample functions unchanged), F and g may be constant arrays, no `dof` (the path's), no
/// `custom_term` (put it in inverse_dynamics) and no discretization scheme (rows hold at the grid points;
/// `guarantee='continuous'` holds them between).
class SecondOrderConstraint : public Constraint {
 public:
  using Options = SecondOrderOptions;

  /// `functions` with inverse_dynamics set, F or F_constant, g or g_constant (a constant F or g is
  /// checked here: shapes and entries).
  SecondOrderConstraint(std::shared_ptr<const SecondOrderFunctions> functions, Options options);

  // docstrings.txt @@ SecondOrderConstraint.__init__
  /// @param inverse_dynamics w = f(q, qd, qdd): arrays (m, n) -> (m, nw).
  /// @param F (r, nw): F(q): (m, n) -> (m, r, nw), or constant.
  /// @param g (r,): g(q): (m, n) -> (m, r), or constant; +inf for an absent row.
  SecondOrderConstraint(SecondOrderFunctions::InverseDynamics inverse_dynamics, SecondOrderFunctions::OfQ F,
                        SecondOrderFunctions::OfQ g, SecondOrderOptions options = SecondOrderOptions());

  // docstrings.txt @@ SecondOrderConstraint.torque_limits
  /// @brief Torque limits tau_min <= inverse_dynamics(q, q̇, q̈) <= tau_max (eq. 15) from your own dynamics: F =
  /// [e_0; -e_0; e_1; ...], g = [τ_max,0; -τ_min,0; ...] (TorqueLimits' rows, in its order), family "torque",
  /// labels "torque <joint> upper/lower" (the problem's joint names, "joint j" without).
  ///
  /// @param tau_min,tau_max (n,): N·m (N); ±inf for none.
  /// @param scale,margin The limits are scale·[tau_min, tau_max] shrunk by margin on each side (as TorqueLimits).
  static std::shared_ptr<const SecondOrderConstraint> torque_limits(
      std::shared_ptr<const SecondOrderFunctions> functions, const Eigen::VectorXd& tau_min,
      const Eigen::VectorXd& tau_max, double scale = 1.0, double margin = 0.0,
      std::vector<std::string> joint_names = {});
  // docstrings.txt @@ SecondOrderConstraint.torque_limits
  /// @brief Torque limits tau_min <= inverse_dynamics(q, q̇, q̈) <= tau_max (eq. 15) from your own dynamics: F =
  /// [e_0; -e_0; e_1; ...], g = [τ_max,0; -τ_min,0; ...] (TorqueLimits' rows, in its order), family "torque",
  /// labels "torque <joint> upper/lower" (the problem's joint names, "joint j" without).
  ///
  /// @param inverse_dynamics τ = f(q, qd, qdd): arrays (m, n) -> (m, n).
  /// @param tau_min,tau_max (n,): N·m (N); ±inf for none.
  /// @param scale,margin The limits are scale·[tau_min, tau_max] shrunk by margin on each side (as TorqueLimits).
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
  // docstrings.txt @@ SecondOrderConstraint.tau_min
  /// (n,): torque_limits' limits after scale and margin; None otherwise.
  const Eigen::VectorXd& tau_min() const { return tau_min_; }
  // docstrings.txt @@ SecondOrderConstraint.tau_max
  /// (n,): torque_limits' limits after scale and margin; None otherwise.
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
