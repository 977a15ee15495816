// The physical rows of a contact force set at one state: what ForceDistribution::Centre takes the
// analytic centre of (contact_checks.cpp's force_distribution).
#include <algorithm>
#include <cmath>
#include <vector>

#include "pathpace/constraints/contact_constraint.hpp"
#include "constraints/contact_tangents.hpp"

namespace pathpace {

void ContactConstraint::physical_rows(const std::vector<Eigen::Isometry3d>& T, const Eigen::MatrixXd& J,
                                      const Eigen::VectorXd& tau, Eigen::MatrixXd& A, Eigen::VectorXd& b,
                                      Eigen::MatrixXd& G, Eigen::VectorXd& h) const {
  const int n = robot_->nq(), m = static_cast<int>(contacts_.size()), k = options_.cone_edges;
  const Eigen::MatrixXd JT = J.transpose();  // (nq, 3 m): τ = τ_id - Jᵀ f (eq. 17 at x, u of the motion)
  const double tiny = 1e-13 * std::max(1.0, JT.cwiseAbs().maxCoeff());
  std::vector<Eigen::VectorXd> eq_rows, in_rows;
  std::vector<double> eq_rhs, in_rhs;
  auto add_row = [&](const Eigen::VectorXd& row, double rhs) {  // row·f <= rhs, scaled to a unit row
    const double len = row.norm();
    if (!(len > tiny)) return;  // no force reaches it: the LP decides its feasibility
    in_rows.push_back(row / len);
    in_rhs.push_back(rhs / len);
  };
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd row = JT.row(j).transpose();
    const double lo = phys_tau_min_[j], hi = phys_tau_max_[j];
    if (lo == hi) {  // an unactuated joint: Jᵀ f = τ_id - lo exactly
      if (row.norm() > tiny) {
        eq_rows.push_back(row);
        eq_rhs.push_back(tau[j] - lo);
      }
      continue;
    }
    if (std::isfinite(lo)) add_row(row, tau[j] - lo);    // τ >= lo
    if (std::isfinite(hi)) add_row(-row, hi - tau[j]);  // τ <= hi
  }
  // The k-edged pyramid of μ inscribed in the friction cone (the LP's generators with friction_margin 0):
  // facet e lies between edges e and e+1, at distance μ f_n cos(π/k) from the axis along their bisector.
  for (int i = 0; i < m; ++i) {
    const Contact& c = contacts_[static_cast<size_t>(i)];
    const Eigen::Vector3d& nrm = c.normal;
    Eigen::Vector3d t1, t2;
    detail::contact_tangents(nrm, t1, t2);
    const Eigen::Matrix3d R = normal_frame(static_cast<size_t>(i), T);
    for (int f = 0; f < k; ++f) {
      const double phi = 2.0 * M_PI * (f + 0.5) / k;
      const Eigen::Vector3d a = c.friction * std::cos(M_PI / k) * nrm - (std::cos(phi) * t1 + std::sin(phi) * t2);
      Eigen::VectorXd row = Eigen::VectorXd::Zero(3 * m);
      row.segment<3>(3 * i) = -(R * a);
      add_row(row, 0.0);
    }
    // A stand-in ceiling keeps the set bounded (internal forces between contacts that no torque row
    // limits would let the centre run off); at cap it hardly moves the centre.
    Eigen::VectorXd row = Eigen::VectorXd::Zero(3 * m);
    row.segment<3>(3 * i) = R * nrm;
    add_row(row, options_.cap);
  }
  A.resize(static_cast<Eigen::Index>(eq_rows.size()), 3 * m);
  b.resize(A.rows());
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    A.row(r) = eq_rows[static_cast<size_t>(r)].transpose();
    b[r] = eq_rhs[static_cast<size_t>(r)];
  }
  G.resize(static_cast<Eigen::Index>(in_rows.size()), 3 * m);
  h.resize(G.rows());
  for (Eigen::Index r = 0; r < G.rows(); ++r) {
    G.row(r) = in_rows[static_cast<size_t>(r)].transpose();
    h[r] = in_rhs[static_cast<size_t>(r)];
  }
}

}  // namespace pathpace
