#include "lp/analytic_centre.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "lp/projection.hpp"

namespace pathpace::detail {
namespace {

// Phase I: maximise δ subject to A y = b, G y + δ <= h (columns y free, then δ <= a stand-in cap).
int max_min_slack(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& G, const Eigen::VectorXd& h,
                  PolytopeProjector& solver, Eigen::VectorXd& y, double& depth) {
  const Eigen::Index n = G.cols(), ne = A.rows(), ni = G.rows();
  const double inf = std::numeric_limits<double>::infinity();
  PolytopeLp lp;
  lp.A.setZero(ne + ni, n + 1);
  lp.A.topLeftCorner(ne, n) = A;
  lp.A.bottomLeftCorner(ni, n) = G;
  lp.A.bottomRightCorner(ni, 1).setOnes();
  lp.row_lo.resize(ne + ni);
  lp.row_hi.resize(ne + ni);
  lp.row_lo.head(ne) = b;
  lp.row_hi.head(ne) = b;
  lp.row_lo.tail(ni).setConstant(-inf);
  lp.row_hi.tail(ni) = h;
  lp.col_lo = Eigen::VectorXd::Constant(n + 1, -inf);
  lp.col_hi = Eigen::VectorXd::Constant(n + 1, inf);
  lp.col_hi[n] = 1e12;
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n + 1), z;
  c[n] = 1.0;
  const int st = solver.maximize(lp, c, z);
  if (st != 1) return st;
  y = z.head(n);
  depth = z[n];
  return 1;
}

}  // namespace

CentreResult analytic_centre(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& G,
                             const Eigen::VectorXd& h, double empty_tol, PolytopeProjector& solver, Eigen::VectorXd& y) {
  CentreResult out;
  out.depth = -1.0;
  const Eigen::Index n = G.cols();
  // A's null space Z (QR of Aᵀ with column pivoting) and the projection onto A y = b.
  Eigen::MatrixXd Z = Eigen::MatrixXd::Identity(n, n);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  const double bscale = std::max(1.0, b.size() ? b.cwiseAbs().maxCoeff() : 0.0);
  if (A.rows() > 0) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A.transpose());
    qr.setThreshold(1e-12);
    const Eigen::Index r = qr.rank();
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
    Z = Q.rightCols(n - r);
    cod.setThreshold(1e-12);
    cod.compute(A);
  }
  auto project = [&](Eigen::VectorXd& v) {
    if (A.rows() > 0) v -= cod.solve(A * v - b);
    return A.rows() == 0 || (A * v - b).cwiseAbs().maxCoeff() <= 1e-9 * bscale;
  };
  if (y.size() != n) y = Eigen::VectorXd::Zero(n);
  const bool on_plane = project(y);
  if (!on_plane || !((h - G * y).minCoeff() > 0.0)) {
    out.phase_one = true;
    double depth = 0.0;
    const int st = max_min_slack(A, b, G, h, solver, y, depth);
    if (st == 0) {
      out.status = CentreResult::Status::Infeasible;
      return out;
    }
    if (st < 0) {
      out.status = CentreResult::Status::SolverError;
      return out;
    }
    if (st != 1) return out;  // Failed
    out.depth = depth;
    if (!(depth > empty_tol)) {
      out.status = CentreResult::Status::EmptyInterior;
      return out;
    }
    if (!project(y) || !((h - G * y).minCoeff() > 0.0)) return out;
  }
  // Damped Newton on ψ(z) = -Σ log(h - G (y + Z z)), self-concordant: the step 1/(1+λ) keeps s > 0 and
  // decreases ψ; full steps once λ < 1/4 (quadratic convergence), λ the Newton decrement.
  const Eigen::MatrixXd GZ = G * Z;
  for (int it = 0; it < 200; ++it) {
    const Eigen::VectorXd s = h - G * y;
    if (!(s.minCoeff() > 0.0)) return out;
    const Eigen::VectorXd d = s.cwiseInverse();
    const Eigen::VectorXd g = GZ.transpose() * d;
    const Eigen::MatrixXd M = d.asDiagonal() * GZ;
    const Eigen::MatrixXd H = M.transpose() * M;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
    if (ldlt.info() != Eigen::Success) return out;
    const Eigen::VectorXd dz = -ldlt.solve(g);
    const double lam = std::sqrt(std::max(0.0, -g.dot(dz)));
    if (!std::isfinite(lam)) return out;
    const double t = lam < 0.25 ? 1.0 : 1.0 / (1.0 + lam);
    Eigen::VectorXd next = y + t * (Z * dz);
    if (!((h - G * next).minCoeff() > 0.0)) next = y + (0.5 * t) * (Z * dz);
    y = next;
    out.newton_steps = it + 1;
    if (lam < 1e-10) {
      out.status = CentreResult::Status::Centre;
      return out;
    }
  }
  return out;  // no convergence: Failed
}

}  // namespace pathpace::detail
