// ContactConstraint's LPs (sec. IV.C, eq. 19): the reduction of its points, the layout of an LP's
// variables and rows, the rows at one grid point, and the names of what binds an edge.
#include "pathpace/constraints/contact_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <Eigen/SVD>

#include "base/validate.hpp"
#include "geometry/convex_hull.hpp"
#include "lp/projection.hpp"
#include "pathpace/errors.hpp"

namespace pathpace {

// The exact reduction: group the points by (link, body, other body, normal, μ); a group whose points
// lie in one plane keeps the vertices of their convex hull in that plane. A force f at p = Σ α_j p_j (α
// a convex combination) has the same generalized force Jᵀ(p) f = Σ α_j Jᵀ(p_j) f (Jᵀ f is affine in p
// for a point of one body: the wrench (f, p × f)), and α_j f lies in the same cone; so the hull
// vertices generate every force the group can. The sum of normal forces is unchanged, so a per-link
// minimum survives. The shifted cone (cone_offset) does not change this: its offsets cone_offset·n_i
// are a constant wrench, kept over every point in lp_point. A per-point minimum d = min_normal_force -
// cone_offset > 0 on the cone weights splits each f_i into a point of the cone's cross-section at
// n·f = d plus a force in the cone: the latter reduce to the hull vertices, the former are d·n_i (a
// constant wrench) plus, for an even k, k/2 weights in [-d, d] per point (docs/method.md). An odd k
// has no such zonotope: every point enters, with its row.
void ContactConstraint::reduce_contacts() {
  const int k = options_.cone_edges;
  const double section_min = options_.min_normal_force - options_.cone_offset;
  const bool per_point = section_min > 0.0;
  std::vector<char> keep(contacts_.size(), 1), section(contacts_.size(), 0);
  if (!per_point || k % 2 == 0) {
    std::map<std::tuple<std::string, int, int, double, double, double, double>, std::vector<int>> groups;
    for (size_t i = 0; i < contacts_.size(); ++i) {
      const Eigen::Vector3d& nrm = contacts_[i].normal;
      groups[{contacts_[i].link, body_[i], other_body_[i], nrm.x(), nrm.y(), nrm.z(), contacts_[i].friction}].push_back(
          static_cast<int>(i));
    }
    for (const auto& [key, members] : groups) {
      if (members.size() < 4) continue;
      Eigen::Matrix3Xd P(3, members.size());
      for (size_t j = 0; j < members.size(); ++j) P.col(static_cast<Eigen::Index>(j)) = point_in_body_[static_cast<size_t>(members[j])];
      const Eigen::Vector3d mean = P.rowwise().mean();
      P.colwise() -= mean;
      Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(P, Eigen::ComputeFullU);
      const Eigen::Vector3d sv = svd.singularValues();
      if (sv[0] == 0.0) {  // all at one point: one of them (with a per-point minimum: all, with their rows)
        if (per_point) continue;
        for (size_t j = 1; j < members.size(); ++j) keep[static_cast<size_t>(members[j])] = 0;
        continue;
      }
      if (sv[2] > 1e-12 * sv[0]) continue;  // not flat: keep every point
      const Eigen::Vector3d e1 = svd.matrixU().col(0), e2 = svd.matrixU().col(1);
      std::vector<detail::Vertex> flat(members.size());
      for (size_t j = 0; j < members.size(); ++j) {
        const Eigen::Vector3d d = P.col(static_cast<Eigen::Index>(j));
        flat[j] = {e1.dot(d), e2.dot(d)};
      }
      std::vector<int> hull;
      detail::convex_hull(flat, hull);
      // With a per-point minimum the reduction trades k weights and a row per point for k/2 weights per
      // point plus the hull's cones: worth it unless most points are hull vertices.
      if (per_point && 2 * hull.size() > members.size()) continue;
      for (int j : members) {
        keep[static_cast<size_t>(j)] = 0;
        section[static_cast<size_t>(j)] = per_point ? 1 : 0;
      }
      for (int h : hull) keep[static_cast<size_t>(members[static_cast<size_t>(h)])] = 1;
    }
  }
  for (size_t i = 0; i < contacts_.size(); ++i) {
    if (keep[i]) {
      reduced_.cone.push_back(static_cast<int>(i));
      reduced_.point_row.push_back(per_point && !section[i] ? 1 : 0);
    }
    if (section[i]) reduced_.section.push_back(static_cast<int>(i));
  }
  reduced_.jacobians = reduced_.cone;
  reduced_.jacobians.insert(reduced_.jacobians.end(), reduced_.section.begin(), reduced_.section.end());
}

ContactConstraint::LpLayout ContactConstraint::full_layout(bool every_point_row) const {
  LpLayout out;
  for (size_t i = 0; i < contacts_.size(); ++i) out.cone.push_back(static_cast<int>(i));
  out.point_row.assign(contacts_.size(), options_.min_normal_force > 0.0 || every_point_row ? 1 : 0);
  out.jacobians = out.cone;
  return out;
}

Eigen::Matrix3d ContactConstraint::normal_frame(size_t i, const std::vector<Eigen::Isometry3d>& T) const {
  if (other_body_[i] < 0) return Eigen::Matrix3d::Identity();
  return T[static_cast<size_t>(other_body_[i])].linear() * other_in_body_[i].linear();
}

void ContactConstraint::contact_jacobians(const Eigen::Ref<const Eigen::VectorXd>& q, std::vector<Eigen::Isometry3d>& T,
                                          Eigen::MatrixXd& J, Eigen::Matrix3Xd& gen, const std::vector<int>* use,
                                          bool placed) const {
  thread_local Eigen::Matrix3Xd axes;
  const int m = use ? static_cast<int>(use->size()) : static_cast<int>(contacts_.size()), k = options_.cone_edges;
  if (!placed) robot_->body_placements(q, T);
  robot_->joint_axes(T, axes);
  J.setZero(3 * m, robot_->nq());
  gen.resize(3, m * k);
  for (int i = 0; i < m; ++i) {
    const size_t u = use ? static_cast<size_t>((*use)[static_cast<size_t>(i)]) : static_cast<size_t>(i);
    chain_jacobian(u, T, axes, J.middleRows(3 * i, 3));
    if (other_body_[u] >= 0)
      gen.middleCols(i * k, k) = T[static_cast<size_t>(other_body_[u])].linear() * other_in_body_[u].linear() * local_generators_[u];
    else
      gen.middleCols(i * k, k) = local_generators_[u];
  }
}

namespace {

// out = -scale · Jiᵀ G on the rows `rows` (ascending), the rest of out left as it is (zero: lp_point's
// precondition). Each coefficient's sum in the order of a coefficient-wise product of inner dimension 3.
// Returns the largest |coefficient| written.
template <class JType, class GType, class Out>
double chain_product(const JType& Ji, const GType& G, double scale, const std::vector<int>& rows, Out&& out) {
  double top = 0.0;
  for (Eigen::Index e = 0; e < G.cols(); ++e)
    for (int r : rows) {
      const double v = -(scale * ((Ji(0, r) * G(0, e) + Ji(1, r) * G(1, e)) + Ji(2, r) * G(2, e)));
      out(r, e) = v;
      top = std::max(top, std::abs(v));
    }
  return top;
}

// Zeroes out's coefficients on `rows` below `tiny` in magnitude.
template <class Out>
void zero_tiny(const std::vector<int>& rows, double tiny, Out&& out) {
  for (Eigen::Index e = 0; e < out.cols(); ++e)
    for (int r : rows) out(r, e) = std::abs(out(r, e)) < tiny ? 0.0 : out(r, e);
}

}  // namespace

void ContactConstraint::lp_structure(const LpLayout& layout, int extra, detail::PolytopeLp& lp) const {
  const int n = robot_->nq(), m = static_cast<int>(layout.cone.size()), k = options_.cone_edges;
  const int ms = static_cast<int>(layout.section.size()), h = k / 2;
  const double inf = std::numeric_limits<double>::infinity();
  // Rows: n torque rows, a per-point minimum per contact with point_row, a per-link minimum per link,
  // `extra` more. Columns: x, u, the cone weights, the cross-section weights.
  std::vector<std::string> links;
  std::vector<int> link_of(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) {
    const std::string& l = contacts_[static_cast<size_t>(layout.cone[static_cast<size_t>(i)])].link;
    auto it = std::find(links.begin(), links.end(), l);
    link_of[static_cast<size_t>(i)] = static_cast<int>(it - links.begin());
    if (it == links.end()) links.push_back(l);
  }
  const int point_rows = static_cast<int>(std::count(layout.point_row.begin(), layout.point_row.end(), 1));
  const int link_rows = options_.min_link_normal_force > 0.0 ? static_cast<int>(links.size()) : 0;
  const int cols = 2 + m * k + ms * h, rows = n + point_rows + link_rows + extra;
  lp.A.setZero(rows, cols);
  lp.row_lo = Eigen::VectorXd::Constant(rows, -inf);
  lp.row_hi = Eigen::VectorXd::Constant(rows, inf);
  lp.col_lo = Eigen::VectorXd::Zero(cols);
  lp.col_hi = Eigen::VectorXd::Constant(cols, inf);
  lp.col_hi[0] = options_.cap;
  lp.col_lo[1] = -options_.cap;
  lp.col_hi[1] = options_.cap;
  lp.stand_in = options_.cap;
  // The cross-section at n·f = d (d = min_normal_force - cone_offset): f = d n + Σ_m β_m w_m with
  // β_m in [-d, d] (w_m: μ' times half an edge of the unit k-gon, local_half_edges_).
  const double d = options_.min_normal_force - options_.cone_offset;
  lp.col_lo.tail(ms * h).setConstant(-1.0);
  lp.col_hi.tail(ms * h).setConstant(1.0);
  // n·f_i = Σ_e λ_ie since n·g_ie = 1 (sec. V.D's minimum normal force, per point and per link).
  // With the shifted cone, n·f_i = cone_offset + Σ_e λ_ie; with a cross-section, n·f_i = cone_offset + d
  // + (its cone part's weights, on the hull vertices). A link's sum counts the offsets of every one of
  // its points, those the reduction left out of the LPs too.
  for (int i = 0, r = n; i < m; ++i) {
    if (!layout.point_row[static_cast<size_t>(i)]) continue;
    lp.A.block(r, 2 + i * k, 1, k).setOnes();
    lp.row_lo[r++] = options_.min_normal_force - options_.cone_offset;
  }
  for (int l = 0; l < link_rows; ++l) {
    const std::string& name = links[static_cast<size_t>(l)];
    auto on = [&](int c) { return contacts_[static_cast<size_t>(c)].link == name; };
    const auto on_link = std::count_if(contacts_.begin(), contacts_.end(), [&](const Contact& c) { return c.link == name; });
    const auto in_section = std::count_if(layout.section.begin(), layout.section.end(), on);
    lp.row_lo[n + point_rows + l] = options_.min_link_normal_force - options_.cone_offset * static_cast<double>(on_link) -
                                    d * static_cast<double>(in_section);
  }
  for (int i = 0; i < m && link_rows > 0; ++i)
    lp.A.block(n + point_rows + link_of[static_cast<size_t>(i)], 2 + i * k, 1, k).setOnes();
}

void ContactConstraint::chain_jacobian(size_t u, const std::vector<Eigen::Isometry3d>& T, const Eigen::Matrix3Xd& axes,
                                       Eigen::Ref<Eigen::MatrixXd> Ji) const {
  for (int r : moving_[u]) {  // three stores, not a run-time-length column's memset
    Ji(0, r) = 0.0;
    Ji(1, r) = 0.0;
    Ji(2, r) = 0.0;
  }
  const Eigen::Vector3d p = (body_[u] >= 0 ? T[static_cast<size_t>(body_[u])] : Eigen::Isometry3d::Identity()) * point_in_body_[u];
  if (body_[u] >= 0) robot_->add_point_jacobian(T, axes, body_[u], p, 1.0, Ji);
  // The reaction acts on other_link at the same world point (eq. 17 with both bodies moving).
  if (other_body_[u] >= 0) robot_->add_point_jacobian(T, axes, other_body_[u], p, -1.0, Ji);
}

void ContactConstraint::lp_point(const LpLayout& layout, const Eigen::Ref<const Eigen::VectorXd>& q,
                                 const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
                                 const Eigen::Ref<const Eigen::VectorXd>& c, detail::PolytopeLp& lp) const {
  thread_local std::vector<Eigen::Isometry3d> T;
  thread_local Eigen::MatrixXd Ji;
  thread_local Eigen::Matrix3Xd axes, gen, edges;
  const int n = robot_->nq(), m = static_cast<int>(layout.cone.size()), k = options_.cone_edges, h = k / 2;
  // eq. (17): τ = a x + b u + c - Σ J_iᵀ f_i, with τ eliminated into row bounds (sec. IV.B).
  lp.A.col(0).head(n) = a;  // the minimum-normal-force rows below n keep zeros in x and u
  lp.A.col(1).head(n) = b;
  robot_->body_placements(q, T);
  robot_->joint_axes(T, axes);  // once for every point: a sole's points share their leg's axes
  // One contact's J_i at a time in Ji (3 x n), on the columns of the joints that move it only
  // (chain_jacobian): J_i is zero on every other column, and nothing below reads them (a foot's point
  // moves with its leg and the base, a third of a humanoid's joints).
  if (Ji.cols() != n) Ji.setZero(3, n);
  // -J_iᵀ g_ie, one product of inner dimension 3 per coefficient, on those rows; the rest of the block
  // stays zero from lp_structure. `top`: the largest |coefficient| of the torque rows.
  double top = 0.0;
  for (int r = 0; r < n; ++r) top = std::max(top, std::max(std::abs(a[r]), std::abs(b[r])));
  for (int i = 0; i < m; ++i) {
    const size_t u = static_cast<size_t>(layout.cone[static_cast<size_t>(i)]);
    chain_jacobian(u, T, axes, Ji);
    const bool turned = other_body_[u] >= 0;  // generators in other_link's frame, turned into the world
    if (turned) gen.noalias() = T[static_cast<size_t>(other_body_[u])].linear() * other_in_body_[u].linear() * local_generators_[u];
    top = std::max(top, chain_product(Ji, turned ? gen : local_generators_[u], 1.0, moving_[u], lp.A.block(0, 2 + i * k, n, k)));
  }
  lp.row_lo.head(n) = tau_min_ - c;
  lp.row_hi.head(n) = tau_max_ - c;
  if (options_.cone_offset > 0.0) {
    // The shifted cone: f_i = cone_offset n_i + Σ_e λ_ie g_ie at every contact, reduced or not, so that
    // τ = a x + b u + c - w - Σ J_iᵀ G_i λ_i with the constant w = cone_offset Σ_i J_iᵀ n_i (eq. 17),
    // moved into the row bounds like c.
    const Eigen::VectorXd w = offset_torques(q, &T);
    lp.row_lo.head(n) += w;
    lp.row_hi.head(n) += w;
  }
  if (!layout.section.empty()) {
    // Each section point's part d n_i + Σ_m β_im w_im: the constant d Σ J_iᵀ n_i into the row bounds,
    // the k/2 weights' columns -J_iᵀ w_im.
    const double d = options_.min_normal_force - options_.cone_offset;
    Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
    for (size_t j = 0; j < layout.section.size(); ++j) {
      const size_t u = static_cast<size_t>(layout.section[j]);
      chain_jacobian(u, T, axes, Ji);
      const Eigen::Matrix3d R = normal_frame(u, T);
      edges.noalias() = R * local_half_edges_[u];
      top = std::max(top, chain_product(Ji, edges, d, moving_[u], lp.A.block(0, 2 + m * k + static_cast<Eigen::Index>(j) * h, n, h)));
      const Eigen::Vector3d nw = R * contacts_[u].normal;
      for (int r : moving_[u]) w[r] += Ji.col(r).dot(nw);
    }
    lp.row_lo.head(n) += d * w;
    lp.row_hi.head(n) += d * w;
  }
  // Rounding residue (1e-17 where a joint axis is orthogonal to a force) is not a coefficient: as a
  // pivot it makes the simplex basis ill-conditioned and its optimum miss the polytope by 1e-5. Only
  // the coefficients written above can be such residue (every other one is an exact zero); a maximum
  // and a select do not round, so the order does not matter.
  if (n == 0) return;
  const double tiny = 1e-13 * top;
  auto xu = lp.A.topLeftCorner(n, 2);
  xu = (xu.array().abs() < tiny).select(0.0, xu);
  for (int i = 0; i < m; ++i)
    zero_tiny(moving_[static_cast<size_t>(layout.cone[static_cast<size_t>(i)])], tiny, lp.A.block(0, 2 + i * k, n, k));
  for (size_t j = 0; j < layout.section.size(); ++j)
    zero_tiny(moving_[static_cast<size_t>(layout.section[j])], tiny,
              lp.A.block(0, 2 + m * k + static_cast<Eigen::Index>(j) * h, n, h));
}

Eigen::VectorXd ContactConstraint::offset_torques(const Eigen::Ref<const Eigen::VectorXd>& q,
                                                  const std::vector<Eigen::Isometry3d>* placed) const {
  thread_local std::vector<Eigen::Isometry3d> own;
  thread_local Eigen::MatrixXd J, Jg;
  thread_local Eigen::Matrix3Xd gen;
  // A link's point Jacobian is affine in the point (add_point_jacobian), so the contacts of one link
  // under one world-fixed normal add up to their count times the Jacobian at their mean point: one
  // Jacobian per such group (a sole), not one per point (offset_groups_). A contact on two moving bodies
  // keeps its own (offset_moving_).
  if (!placed) robot_->body_placements(q, own);
  const std::vector<Eigen::Isometry3d>& T = placed ? *placed : own;
  const int nq = robot_->nq();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(nq);
  if (!offset_moving_.empty()) {
    thread_local std::vector<Eigen::Isometry3d> Tm;  // contact_jacobians takes placements it could write
    Tm = T;
    contact_jacobians(q, Tm, J, gen, &offset_moving_, true);
    for (size_t j = 0; j < offset_moving_.size(); ++j) {
      const size_t i = static_cast<size_t>(offset_moving_[j]);
      // The normal in the world: other_link's turned into the world.
      const Eigen::Vector3d n = T[static_cast<size_t>(other_body_[i])].linear() * other_in_body_[i].linear() * contacts_[i].normal;
      w.noalias() += J.middleRows(3 * static_cast<Eigen::Index>(j), 3).transpose() * n;
    }
  }
  for (const OffsetGroup& g : offset_groups_) {
    Jg.setZero(3, nq);
    robot_->add_point_jacobian(T, g.body, T[static_cast<size_t>(g.body)] * Eigen::Vector3d(g.sum / g.count), g.count, Jg);
    w.noalias() += Jg.transpose() * g.normal;
  }
  return options_.cone_offset * w;
}

std::vector<std::string> ContactConstraint::binding_names(const LpLayout& layout) const {
  // The layout of lp_structure: n torque rows, then the per-point and per-link minimum normal force rows;
  // columns x, u, then the k cone-edge weights of each cone contact, the k/2 weights of each section
  // contact. Entry 2r / 2r + 1: row r at its lower / upper bound; then one entry per column.
  const std::vector<int>& use = layout.cone;
  const int n = robot_->nq(), m = static_cast<int>(use.size()), k = options_.cone_edges;
  auto name_of = [&](int contact) {
    const Contact& c = contacts_[static_cast<size_t>(contact)];
    std::ostringstream os;
    os.precision(4);
    os << "link '" << c.link << "' point (" << c.point.x() << ", " << c.point.y() << ", " << c.point.z() << ")";
    return os.str();
  };
  auto contact_name = [&](int i) { return name_of(use[static_cast<size_t>(i)]); };
  std::vector<std::string> links;
  for (int i = 0; i < m; ++i) {
    const std::string& l = contacts_[static_cast<size_t>(use[static_cast<size_t>(i)])].link;
    if (std::find(links.begin(), links.end(), l) == links.end()) links.push_back(l);
  }
  const int link_rows = options_.min_link_normal_force > 0.0 ? static_cast<int>(links.size()) : 0;
  std::vector<std::string> out;
  for (int j = 0; j < n; ++j) {
    const std::string& name = robot_->joint_names()[static_cast<size_t>(j)];
    const bool unactuated = tau_min_[j] == 0.0 && tau_max_[j] == 0.0;
    out.push_back(unactuated ? "balance of unactuated " + name : "torque " + name + " lower");
    out.push_back(unactuated ? "balance of unactuated " + name : "torque " + name + " upper");
  }
  for (int i = 0; i < m; ++i) {
    if (!layout.point_row[static_cast<size_t>(i)]) continue;
    out.push_back("minimum normal force at " + contact_name(i));
    out.push_back("minimum normal force at " + contact_name(i));
  }
  for (int l = 0; l < link_rows; ++l) {
    out.push_back("minimum normal force on link '" + links[static_cast<size_t>(l)] + "'");
    out.push_back("minimum normal force on link '" + links[static_cast<size_t>(l)] + "'");
  }
  out.push_back("sdot^2 >= 0");
  out.push_back("sddot");
  for (int i = 0; i < m; ++i)
    for (int e = 0; e < k; ++e) out.push_back("friction at " + contact_name(i));
  // A cross-section weight at its bound: the point pushes its minimum and uses its friction there.
  for (int j : layout.section)
    for (int e = 0; e < k / 2; ++e) out.push_back("minimum normal force at " + name_of(j));
  return out;
}

std::string ContactConstraint::binding_label(const LpLayout& layout, const std::vector<std::string>& names, int code) const {
  const int rows_entries = static_cast<int>(names.size()) - 2 - static_cast<int>(layout.cone.size()) * options_.cone_edges -
                           static_cast<int>(layout.section.size()) * (options_.cone_edges / 2);
  size_t i = names.size();
  if (code == detail::kBindingUnknown) return "contact forces";
  if (detail::binding_is_row(code)) i = static_cast<size_t>(code);
  else i = static_cast<size_t>(rows_entries + detail::binding_column(code));
  return i < names.size() ? names[i] : std::string("contact forces");
}

}  // namespace pathpace
