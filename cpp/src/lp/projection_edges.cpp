// PolytopeProjector::Run's edge expansion (sec. IV.C): the hull's uncertified edges, each certified by an
// endpoint's ranging, by the approximation or by its LP, and what binds there.
#include "lp/projection_run.hpp"
#include "lp/binding_rule.hpp"

#include "lp/glpk_util.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glpk.h>

namespace pathpace::detail {

// projection_tolerance: every LP optimum p found along v gives the outer half-plane v·z <= v·p of the
// shadow. Beyond an edge (a, b) with normal n, those of a and b (v_a before n before v_b, counter-
// clockwise) leave the triangle a, apex, b; in every direction d between v_a and v_b the shadow's support
// exceeds the hull's by at most d·(apex - a) (or - b) <= the apex's height above the edge. An edge whose
// apex lies within `approx` of it is final: the hull stays (an inner set, conservative).
// Except next to the rest state x = ṡ² = 0: there the slice of s̈ decides whether the path can start or
// stop at the point at all, and is often far shorter than the polygon's size (which the approximation is
// relative to). Without it, an inner polygon that kept only s̈ < 0 at rest made a feasible Talos squat
// infeasible; edges from a vertex at x's lower bound are always solved, so that slice and the edges on
// either side of it stay exact.
bool PolytopeProjector::Run::within_approximation(const Pending& e) const {
  if (!(approx_ > 0.0) || e.from == e.to) return false;
  const Vertex &a = points_[static_cast<size_t>(e.from)], &b = points_[static_cast<size_t>(e.to)];
  if (std::isfinite(xlo_) && std::min(a.x, b.x) <= xlo_ + tol_) return false;
  const Vertex &da = support_[static_cast<size_t>(e.from)], &db = support_[static_cast<size_t>(e.to)];
  const double det = da.x * db.y - da.y * db.x;
  if (!(da.x * e.nu - da.y * e.nx > 0.0) || !(e.nx * db.y - e.nu * db.x > 0.0) || !(det > 0.0)) return false;
  const double ra = da.x * a.x + da.y * a.y, rb = db.x * b.x + db.y * b.y;
  const double px = (ra * db.y - rb * da.y) / det, pu = (da.x * rb - db.x * ra) / det;
  return e.nx * px + e.nu * pu - e.offset <= approx_;
}

// The constraint that holds the shadow at an edge: at the certifying LP's optimum, the inequality row or
// column bound with the largest dual (a row's dual per unit of its normalised row), with its side.
// False: a GLPK error.
bool PolytopeProjector::Run::binding(int& code) {
  code = kBindingUnknown;
  const double* norm = row_norm_.data();
  if (last_dense_) {  // the same rule on the dense simplex's statuses and reduced costs
    const DenseSimplex& ds = self_.dense_engine_;
    const std::vector<signed char>& st = ds.state().stat;
    code = binding_rule(in_, norm, 0, [&](int k) { return st[static_cast<size_t>(k)]; },
                        [&](int k) { return ds.reduced_cost(k); });
    return true;
  }
  return guarded([&] { code = glpk_binding(lp_, in_, norm, 0); });
}

int glpk_binding(glp_prob* lp, const PolytopeLp& in, const double* row_norm, int first_column) {
  const int rows = static_cast<int>(in.A.rows());
  return binding_rule(
      in, row_norm, first_column,
      [&](int k) { return k < rows ? glp_get_row_stat(lp, k + 1) : glp_get_col_stat(lp, k - rows + 1); },
      [&](int k) { return k < rows ? glp_get_row_dual(lp, k + 1) : glp_get_col_dual(lp, k - rows + 1); });
}

// Ranging's certificate (see Ranging): the basis of rg is optimal along (nx, nu), to 1e-11 in every
// reduced cost (GLPK stops at tol_dj = 1e-10); `code` is then what binding() would say there.
bool PolytopeProjector::Run::range_certifies(const Ranging& rg, double nx, double nu, int& code) const {
  if (rg.var.empty()) return false;
  constexpr double kEps = 1e-11;
  for (size_t t = 0; t < rg.var.size(); ++t) {
    const double d = nx * rg.A[t] + nu * rg.B[t];
    const int st = rg.stat[t];
    if ((st == GLP_NL && d > kEps) || (st == GLP_NU && d < -kEps) || (st == GLP_NF && std::abs(d) > kEps)) return false;
  }
  code = kBindingUnknown;
  double best = 0.0;
  for (size_t t = 0; t < rg.var.size(); ++t) {
    const int k = rg.var[t];
    const double d = std::abs(nx * rg.A[t] + nu * rg.B[t]);
    if (k <= rows_) {
      const int i = k - 1;
      if (rg.stat[t] == GLP_NS || in_.row_lo[i] == in_.row_hi[i]) continue;
      if (d * row_norm_[i] > best) best = d * row_norm_[i], code = 2 * i + (rg.stat[t] == GLP_NU ? 1 : 0);
    } else if (d > best) {
      best = d;
      code = -(k - rows_);
    }
  }
  return true;
}

// The hull's uncertified directions: each edge's outward normal, and a segment's two ends.
void PolytopeProjector::Run::directions() {
  pending_.clear();
  const size_t h = hull_.size();
  auto add = [&](int from, int to, double nx, double nu) {
    if (certified_.count({from, to}) != 0) return;
    const double len = std::hypot(nx, nu);
    if (!(len > 0.0)) return;
    nx /= len;
    nu /= len;
    // The hull's own support value in this direction: attained at the edge's ends (a convex hull).
    const Vertex &a = points_[static_cast<size_t>(from)], &b = points_[static_cast<size_t>(to)];
    pending_.push_back({from, to, nx, nu, std::max(nx * a.x + nu * a.y, nx * b.x + nu * b.y)});
  };
  if (h == 1) return;  // three support points coincide: the shadow is that point
  for (size_t e = 0; e < h; ++e) {
    const int i = hull_[e], j = hull_[(e + 1) % h];
    const Vertex &a = points_[static_cast<size_t>(i)], &b = points_[static_cast<size_t>(j)];
    add(i, j, b.y - a.y, -(b.x - a.x));  // outward normal of a counter-clockwise edge
  }
  if (h == 2) {  // a segment: its two ends too
    const Vertex &a = points_[static_cast<size_t>(hull_[0])], &b = points_[static_cast<size_t>(hull_[1])];
    add(hull_[0], hull_[0], a.x - b.x, a.y - b.y);
    add(hull_[1], hull_[1], b.x - a.x, b.y - a.y);
  }
  if (focus_) focus_directions();
}

// With a focus, of the hull's uncertified directions only those that settle a focus point: per point not yet
// inside the hull or beyond a certified edge, the edge it lies farthest beyond. Its LP either certifies that
// edge or finds a support point; one such edge per point and step, so that a point far outside costs a chain
// of LPs towards it, not every edge it can see. A support line does not settle a point: the timing comes
// from rows that include it, and lies beyond it only by the solver's tolerance, which may exceed ours, while
// the shadow near the point may be far inside it.
void PolytopeProjector::Run::focus_directions() {
  std::vector<Pending> kept;
  for (const Vertex& q : *focus_) {
    bool settled = false;
    for (size_t i = 0; i < certified_lines_.size() && !settled; ++i) {
      const Pending& d = certified_lines_[i].first;
      settled = d.nx * q.x + d.nu * q.y > d.offset + tol_;
    }
    if (settled) continue;
    const Pending* worst = nullptr;
    double far = tol_;
    for (const Pending& d : pending_) {
      // Not an edge whose ends are one point to the tolerance (two initial LPs that found one vertex): its
      // normal is rounding, and the LP along it finds the far side of the shadow.
      const Vertex &a = points_[static_cast<size_t>(d.from)], &b = points_[static_cast<size_t>(d.to)];
      if (d.from != d.to && std::hypot(a.x - b.x, a.y - b.y) <= tol_) continue;
      const double beyond = d.nx * q.x + d.nu * q.y - d.offset;
      if (beyond > far) far = beyond, worst = &d;
    }
    if (!worst) continue;  // inside the hull (to the tolerance)
    bool listed = false;
    for (const Pending& k : kept) listed = listed || (k.from == worst->from && k.to == worst->to);
    if (!listed) kept.push_back(*worst);
  }
  pending_ = std::move(kept);
}

void PolytopeProjector::Run::certify(const Pending& d, int code) {
  certified_[{d.from, d.to}] = code;
  if (focus_) certified_lines_.emplace_back(d, code);
}

// Edge expansion: the hull's uncertified directions, recomputed whenever a new support point changes
// the hull, until every edge is certified (or the projection is incomplete).
PolytopeProjector::Run::Step PolytopeProjector::Run::expand() {
  hull_changed();
  while (out_.complete) {
    directions();
    if (pending_.empty()) break;
    const Step s = certify_pending();
    if (s == Step::Stop) return s;
    if (s == Step::Again) hull_changed();
  }
  return Step::Ok;
}

// Each pending direction in turn: certified by an endpoint's ranging, by the approximation, or by its LP
// finding nothing beyond the edge. Again: the LP found a new support point (the hull changes).
PolytopeProjector::Run::Step PolytopeProjector::Run::certify_pending() {
  for (const Pending& d : pending_) {
    int code = kBindingUnknown;
    if (range_certifies(ranges_[static_cast<size_t>(d.from)], d.nx, d.nu, code) ||
        range_certifies(ranges_[static_cast<size_t>(d.to)], d.nx, d.nu, code)) {
      ++out_.by_cause.ranged;
      certify(d, code);
      continue;
    }
    if (within_approximation(d)) {
      ++out_.approximate_edges;
      certify(d, kBindingUnknown);  // no LP along it: what binds there is not known
      continue;
    }
    if (out_.lp_solves >= max_lps_) {
      out_.complete = false;
      out_.note = "LP budget (" + std::to_string(max_lps_) + ") ran out with " + std::to_string(pending_.size()) +
                  " edges not certified";
      return Step::Ok;
    }
    Vertex q;
    // From the endpoint whose support direction is nearer the edge's normal.
    const Vertex &sa = support_[static_cast<size_t>(d.from)], &sb = support_[static_cast<size_t>(d.to)];
    const int start = sa.x * d.nx + sa.y * d.nu >= sb.x * d.nx + sb.y * d.nu ? d.from : d.to;
    const int r = extremize(d.nx, d.nu, q, start);
    if (r != 1) ++out_.by_cause.vertex;
    if (r == -2) return glpk_error();
    if (r != 1) {
      // The polytope was non-empty three LPs ago: an 'infeasible' here is a solver failure too.
      out_.complete = false;
      out_.note = "the LP solver did not finish after " + std::to_string(out_.lp_solves) + " LPs";
      return Step::Ok;
    }
    if (d.nx * q.x + d.nu * q.y > d.offset + tol_) {  // strictly outside the hull by more than the tolerance
      ++out_.by_cause.vertex;
      add_point(q, {d.nx, d.nu});
      return Step::Again;
    }
    ++out_.by_cause.certificate;
    if (!binding(code)) return glpk_error();
    certify(d, code);  // nothing of the shadow beyond this edge
  }
  return Step::Ok;
}

}  // namespace pathpace::detail
