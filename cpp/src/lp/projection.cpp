#include "lp/projection_run.hpp"

#include "geometry/convex_hull.hpp"
#include "lp/glpk_util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <glpk.h>

namespace pathpace::detail {

Projection project_polytope(const PolytopeLp& in, double relative_tolerance, int max_lps, double approximation,
                            const std::vector<Vertex>* focus, ProjectionState* state) {
  PolytopeProjector p;
  return p.project(in, relative_tolerance, max_lps, approximation, focus, state);
}

namespace {

// Warm starts across grid points (sec. IV.C) only for LPs of at least this many columns: a restored
// basis is refactorised (about the cost of a few pivots), which pays only where an LP takes many pivots.
constexpr int kRestoreColumns = 200;
// A previous grid point's basis is restored only if its LP's direction is within this many radians.
constexpr double kNear = 0.35;
// Ranging from this many columns on: below, an LP is a few pivots on a tiny basis and costs about what
// the two tableau rows do.
constexpr int kRangingColumns = 30;

}  // namespace

Projection PolytopeProjector::project(const PolytopeLp& in, double relative_tolerance, int max_lps, double approximation,
                                      const std::vector<Vertex>* focus, ProjectionState* state) {
  return Run(*this, in, relative_tolerance, max_lps, approximation, focus, state).project();
}

// A GLPK error (guarded() returned false): the problem is gone with the environment; so is the result.
PolytopeProjector::Run::Step PolytopeProjector::Run::glpk_error() {
  out_.outcome = Projection::Outcome::Failed;
  out_.complete = false;
  out_.note = "GLPK error";
  return Step::Stop;
}

Projection PolytopeProjector::Run::project() {
  const bool resuming = state_ && state_->resumable;
  if (state_) state_->resumable = false;  // until this run keeps its own
  if (!start()) return out_;
  if (resuming) {
    resume();
  } else {
    Step s;
    while ((s = triangle()) == Step::Again)
      if (grow_stand_in() == Step::Stop) return out_;
    if (s == Step::Stop) return out_;
    // An LP that failed in the triangle left an inner set, reported incomplete.
    out_.complete = points_.size() == 3;
  }
  out_.stand_in = stand_in_;
  if (expand() == Step::Stop) return out_;
  // A shadow found only beyond the stand-in bounds is not called exact: there b·u ~ 1e2 with b ~ 1e-8 (the
  // rounding residue of a path derivative), and the LPs' optima were seen to differ from HiGHS's by
  // orders of magnitude along u. What matters is that it is not empty (the status then comes from
  // reachability, which such an s̈ cannot satisfy, not from a false "no forces balance the robot").
  if (stand_in_ != in_.stand_in && out_.complete) {
    out_.complete = false;
    out_.note = "the shadow lies only beyond the stand-in bounds (ill-conditioned LPs there)";
  }
  polygon();
  if (state_) keep_state();
  std::swap(self_.previous_, self_.current_);
  return out_;
}

// Where the last focused run on this polytope left off: its support points (their LPs' ranging is not kept:
// the edges next to them are certified by LPs; their bases are, for the dense simplex to start from).
void PolytopeProjector::Run::resume() {
  const ProjectionState& st = *state_;
  points_ = st.points;
  support_ = st.support;
  support_binding_ = st.binding;
  basis_ = st.basis;
  ranges_.assign(points_.size(), Ranging());
  states_.assign(points_.size(), DenseSimplex::State());
  for (const ProjectionState::Certified& c : st.certified) {
    const Pending d{c.from, c.to, c.nx, c.nu, c.offset};
    certified_[{c.from, c.to}] = c.binding;
    certified_lines_.emplace_back(d, c.binding);
  }
  out_.complete = true;
}

// This run's state for the next (only for the caller's own LP: the stand-in bounds not grown).
void PolytopeProjector::Run::keep_state() {
  ProjectionState& st = *state_;
  st.resumable = out_.outcome == Projection::Outcome::Polygon && stand_in_ == in_.stand_in && sx_ == 1.0 && su_ == 1.0;
  if (!st.resumable) return;
  st.points = points_;
  st.support = support_;
  st.binding = support_binding_;
  st.basis = std::move(basis_);
  if (!st.keep_bases) st.basis.assign(st.points.size(), {});
  st.certified.clear();
  for (const auto& [d, code] : certified_lines_) st.certified.push_back({d.from, d.to, d.nx, d.nu, d.offset, code});
}

// Sizes every buffer the LPs' guarded calls write (glpk_guard.hpp's rule 1); GLPK's problem is loaded by
// load_glpk(), when an LP first needs it.
bool PolytopeProjector::Run::start() {
  // The parameters first: a GLPK error there frees the problem before load() looks at it.
  if (!projection_simplex_parameters(static_cast<int>(in_.A.rows()), static_cast<int>(in_.A.cols()), parm_)) {
    glpk_error();
    return false;
  }
  rows_ = static_cast<int>(in_.A.rows());
  cols_ = static_cast<int>(in_.A.cols());
  total_ = rows_ + cols_;
  // Warm starts across grid points (sec. IV.C): each LP starts from the final basis of the previous grid
  // point's LP in the nearest direction, if one was within kNear radians, by the dual simplex. That basis
  // is optimal for a nearby polytope and direction, so it is (nearly) dual feasible and a few dual pivots
  // restore primal feasibility, where the primal simplex from the basis of the LP just before (another
  // direction) takes many. Any start gives an optimum, so the polygon does not depend on it (a
  // degenerate optimum may be another point of the same edge). load_glpk() decides whether they apply.
  record_ = cols_ >= kRestoreColumns;  // no basis is restored below this size: none is recorded
  self_.current_.clear();
  dual_ = parm_;
  dual_.meth = GLP_DUALP;
  self_.stat_.resize(static_cast<size_t>(total_));
  // The tableau rows of x and u (1-based over every variable, GLPK's numbering).
  for (auto* v : {&self_.tab_val_, &self_.tab_x_, &self_.tab_u_}) v->resize(static_cast<size_t>(total_) + 1);
  self_.tab_ind_.resize(static_cast<size_t>(total_) + 1);
  xlo_ = in_.col_lo[0], xhi_ = in_.col_hi[0], ulo_ = in_.col_lo[1], uhi_ = in_.col_hi[1];
  stand_in_ = in_.stand_in;
  dense_on_ = self_.dense && self_.ranging && cols_ >= kRangingColumns;
  row_norm_ = in_.A.rowwise().norm();  // binding()'s scale of each row
  if (dense_on_) self_.dense_engine_.load(in_);
  return true;
}

// GLPK's problem is loaded only for the first LP that GLPK solves: a grid point whose LPs the dense simplex
// solves from warm bases (project_on_demand's) never needs it. False: a GLPK error.
bool PolytopeProjector::Run::load_glpk() {
  if (lp_) return true;
  const int loaded = self_.load(in_);
  if (loaded < 0) return false;
  lp_ = self_.lp_.get();
  // start()'s warm starts across grid points: the previous grid point's bases, if of this shape.
  same_shape_ = loaded == 1 && !self_.previous_.empty() && cols_ >= kRestoreColumns;
  nonempty_col_.assign(static_cast<size_t>(cols_), 0);
  if (same_shape_)
    for (int j = 0; j < cols_; ++j) nonempty_col_[static_cast<size_t>(j)] = (in_.A.col(j).array() != 0.0).any();
  return true;
}

// The basis to warm-start an LP along `angle` from: the previous grid point's in the nearest direction
// within kNear, unless it would be singular here.
const PolytopeProjector::Basis* PolytopeProjector::Run::warm_basis(double angle) const {
  if (!same_shape_) return nullptr;
  const Basis* from = nullptr;
  double best = kNear;
  for (const Basis& b : self_.previous_) {
    double d = std::abs(b.angle - angle);
    d = std::min(d, 2.0 * M_PI - d);
    if (d < best) best = d, from = &b;
  }
  if (!from) return nullptr;
  // A basic column that is empty in this grid point's matrix (a coefficient rounded to zero) makes
  // the basis singular, which GLPK's factorization was seen to meet with an assertion, not a status.
  for (int j = 0; j < cols_; ++j)
    if (from->stat[static_cast<size_t>(rows_ + j)] == GLP_BS && !nonempty_col_[static_cast<size_t>(j)]) return nullptr;
  return from;
}

// The LP along (vx, vu), inside a guarded call: from `start` by the dual simplex if that basis is dual
// feasible, else from `fallback` (or the current basis) by the primal simplex; then, if kept or ranged,
// the optimal basis into stat_, and if ranged the tableau rows of x and u into tab_x_, tab_u_.
void PolytopeProjector::Run::solve_lp(double vx, double vu, const signed char* start, const signed char* fallback,
                                      bool range, LpPoint& r) {
  glp_set_obj_coef(lp_, 1, vx * sx_);
  glp_set_obj_coef(lp_, 2, vu * su_);
  auto restore = [&](const signed char* b) {
    for (int i = 0; i < rows_; ++i) glp_set_row_stat(lp_, i + 1, b[i]);
    for (int j = 0; j < cols_; ++j) glp_set_col_stat(lp_, j + 1, b[rows_ + j]);
  };
  const glp_smcp* method = &parm_;
  if (start) {
    restore(start);
    // Dual feasible (to the simplex's tolerance): the dual simplex. Otherwise (a degenerate vertex whose
    // reduced costs changed sign) back to the basis of the LP just before (primal feasible within a grid
    // point) and the primal simplex, which from the restored basis was seen to take hundreds of pivots.
    if (glp_warm_up(lp_) == 0 && glp_get_dual_stat(lp_) == GLP_FEAS) method = &dual_;
    else restore(fallback);
  }
  r.st = glpk_solve_robust(lp_, *method, false);
  if (r.st != GLP_OPT) return;
  r.px = glp_get_col_prim(lp_, 1);
  r.pu = glp_get_col_prim(lp_, 2);
  if (!record_ && !range) return;
  signed char* stat = self_.stat_.data();
  glpk_get_basis(lp_, rows_, cols_, stat);
  if (!range || !glp_bf_exists(lp_)) return;
  // The tableau rows of x and u (zero where that column is nonbasic: its reduced cost is then v's own).
  int* tab_ind = self_.tab_ind_.data();
  double* tab_val = self_.tab_val_.data();
  auto tab_row = [&](int col, double* out) {
    for (int k = 0; k <= total_; ++k) out[k] = 0.0;
    if (stat[rows_ + col - 1] != GLP_BS) return;
    const int len = glp_eval_tab_row(lp_, rows_ + col, tab_ind, tab_val);
    for (int t = 1; t <= len; ++t) out[tab_ind[t]] = tab_val[t];
  };
  tab_row(1, self_.tab_x_.data());
  tab_row(2, self_.tab_u_.data());
  r.ranged = true;
}

// eq. (19) along (vx, vu): 1 optimal (p its (x, u)), 0 infeasible, -1 failed, -2 a GLPK error. By the dense
// simplex from the optimal basis of support point `start_point` when it has one, else (or when the dense
// simplex gives up) by GLPK.
int PolytopeProjector::Run::extremize(double vx, double vu, Vertex& p, int start_point) {
  ++out_.lp_solves;
  const double angle = std::atan2(vu, vx);
  if (extremize_dense(vx, vu, p, start_point, angle)) return 1;
  if (!load_glpk()) return -2;
  const Basis* from = warm_basis(angle);
  const signed char* start = from ? from->stat.data() : nullptr;
  const signed char* fallback =
      from ? (self_.current_.empty() ? self_.previous_.back() : self_.current_.back()).stat.data() : nullptr;
  // Ranging only on unscaled columns (its reduced costs are in the LP's own units).
  const bool range = self_.ranging && cols_ >= kRangingColumns && sx_ == 1.0 && su_ == 1.0;
  LpPoint r;
  int iterations = 0;
  if (!guarded([&] {
        const int before = glp_get_it_cnt(lp_);
        solve_lp(vx, vu, start, fallback, range, r);
        iterations = glp_get_it_cnt(lp_) - before;
      }))
    return -2;
  out_.by_cause.pivots += std::max(iterations, 0);
  if (r.st != GLP_OPT) return r.st == GLP_NOFEAS ? 0 : -1;
  p = {sx_ * r.px, su_ * r.pu};
  range_basis(r.ranged);
  // GLPK's optimal basis, for the dense simplex's next LPs (stat_ holds it: range is on with dense_on_).
  last_state_ = DenseSimplex::State();
  if (dense_on_ && r.ranged && self_.dense_engine_.set_basis(self_.stat_.data())) last_state_ = self_.dense_engine_.state();
  if (record_) self_.current_.push_back({angle, self_.stat_});
  return 1;
}

// The dense simplex's LP (see extremize); false: not tried, or given up (counted; GLPK solves it).
bool PolytopeProjector::Run::extremize_dense(double vx, double vu, Vertex& p, int start_point, double angle) {
  last_dense_ = false;
  if (!dense_on_) return false;
  DenseSimplex& ds = self_.dense_engine_;
  if (warm_) {
    // A basis of the previous grid point's LP in this direction: optimal for a nearby polytope, so a few dual
    // pivots restore primal feasibility (maximize's dual phase) and a few primal ones optimality.
    if (!ds.set_basis(warm_, false)) return false;
  } else {
    if (start_point < 0) return false;
    const size_t sp = static_cast<size_t>(start_point);
    if (states_[sp].head.empty()) {
      // A support point of an earlier run (resume): its basis factorised once, then kept like this run's own.
      if (!focus_ || sp >= basis_.size() || basis_[sp].size() != static_cast<size_t>(total_) ||
          !ds.set_basis(basis_[sp].data()))
        return false;
      states_[sp] = ds.state();
    }
    ds.restore(states_[sp]);
  }
  const int before = ds.pivots;
  const int ok = ds.maximize(vx, vu);
  out_.by_cause.pivots += ds.pivots - before;
  if (ok != DenseSimplex::kOptimal) {
    LpCounts& c = out_.by_cause;
    ++c.dense_fallback;
    switch (ok) {
      case DenseSimplex::kIterationCap: ++c.fallback_cap; break;
      case DenseSimplex::kSmallPivot: ++c.fallback_small_pivot; break;
      case DenseSimplex::kUnbounded: ++c.fallback_unbounded; break;
      case DenseSimplex::kSingular: ++c.fallback_singular; break;
      default: ++c.fallback_certificate; break;  // kCertificate (kNoBasis is excluded above)
    }
    return false;
  }
  ++out_.by_cause.dense;
  last_dense_ = true;
  last_state_ = ds.state();
  p = {ds.x(), ds.u()};
  std::copy(last_state_.stat.begin(), last_state_.stat.end(), self_.stat_.begin());
  ds.tableau_xu(self_.tab_x_.data(), self_.tab_u_.data());
  range_basis(true);
  if (record_) self_.current_.push_back({angle, self_.stat_});
  return true;
}

// last_range_ from the basis in stat_ and the tableau rows in tab_x_, tab_u_ (see Ranging).
void PolytopeProjector::Run::range_basis(bool computed) {
  Ranging& rg = last_range_;
  rg = Ranging();
  if (!computed) return;
  const size_t nonbasic = static_cast<size_t>(cols_);  // rows + cols variables, rows of them basic
  rg.var.reserve(nonbasic);
  rg.stat.reserve(nonbasic);
  rg.A.reserve(nonbasic);
  rg.B.reserve(nonbasic);
  for (int k = 1; k <= total_; ++k) {
    const signed char st = self_.stat_[static_cast<size_t>(k - 1)];
    if (st == GLP_BS) continue;
    rg.var.push_back(k);
    rg.stat.push_back(st);
    rg.A.push_back(self_.tab_x_[static_cast<size_t>(k)] + (k == rows_ + 1 ? 1.0 : 0.0));
    rg.B.push_back(self_.tab_u_[static_cast<size_t>(k)] + (k == rows_ + 2 ? 1.0 : 0.0));
  }
}

void PolytopeProjector::Run::add_point(const Vertex& p, const Vertex& direction) {
  if (focus_) {  // its support line is a row of the outer polygon: what binds there names it
    int code = kBindingUnknown;
    if (!binding(code)) code = kBindingUnknown;
    support_binding_.push_back(code);
    basis_.push_back(self_.stat_);  // the LP's optimal basis (extremize leaves it there)
  }
  points_.push_back(p);
  ranges_.push_back(std::move(last_range_));
  support_.push_back(direction);
  states_.push_back(std::move(last_state_));
  last_state_ = DenseSimplex::State();
}

// Initial directions: the vertices of an equilateral triangle (sec. IV.C). They positively span the
// plane, so a shadow whose three support points coincide is that point. An LP that fails here keeps the
// support points found so far (an inner set, reported incomplete). Again: the first LP is infeasible
// with the stand-in bounds, which grow_stand_in() then looks beyond.
PolytopeProjector::Run::Step PolytopeProjector::Run::triangle() {
  for (int i = 0; i < 3; ++i) {
    const double ang = 2.0 * M_PI * i / 3.0;
    Vertex p;
    std::vector<signed char>& warm = self_.triangle_[i];
    warm_ = focus_ && warm.size() == static_cast<size_t>(total_) ? warm.data() : nullptr;
    const int r = extremize(std::cos(ang), std::sin(ang), p, static_cast<int>(points_.size()) - 1);
    warm_ = nullptr;
    if (focus_ && r == 1) warm = self_.stat_;
    ++out_.by_cause.initial;
    if (r == -2) return glpk_error();
    if (r == 0 && i == 0 && (capped(xhi_) || capped(ulo_) || capped(uhi_))) return Step::Again;
    if (r <= 0) {
      const std::string note = "the LP solver did not finish (initial direction " + std::to_string(i) + ")";
      if (!points_.empty()) {  // an LP failed after a feasible one: keep what was found
        out_.note = note;
        return Step::Ok;
      }
      out_.outcome = r == 0 ? Projection::Outcome::Empty : Projection::Outcome::Failed;
      if (r < 0) out_.note = note;
      return Step::Stop;
    }
    add_point(p, {std::cos(ang), std::sin(ang)});
  }
  return Step::Ok;
}

// Infeasible with the stand-in bounds: is it without them? A polytope whose shadow lies only beyond them
// (a grid point where b ~ 1e-8, so that s̈ ~ 1e10 would be needed) is not empty, and calling it empty
// contradicts solve()'s re-check on the full polytope. One feasibility LP without them; if feasible, the
// bounds grow past its point (x, u) and the triangle starts again, from the feasible basis found.
PolytopeProjector::Run::Step PolytopeProjector::Run::grow_stand_in() {
  const double x_hi = capped(xhi_) ? INFINITY : xhi_, u_lo = capped(ulo_) ? -INFINITY : ulo_,
               u_hi = capped(uhi_) ? INFINITY : uhi_;
  ++out_.lp_solves;
  ++out_.by_cause.cap_growth;
  if (!load_glpk()) return glpk_error();
  // The LP changes (bounds grown, columns scaled): the dense simplex's bases are not its own any more.
  dense_on_ = false;
  for (DenseSimplex::State& st : states_) st = DenseSimplex::State();
  int st = -1;
  double fx = 0.0, fu = 0.0;
  const bool ok = guarded([&] {
    glp_set_obj_coef(lp_, 1, 0.0);
    glp_set_obj_coef(lp_, 2, 0.0);
    glpk_set_bounds(lp_, false, 1, xlo_, x_hi);
    glpk_set_bounds(lp_, false, 2, u_lo, u_hi);
    // With GLPK's scaling, for this LP only: with b ~ 1e-8 against forces ~ 1e2 the unscaled simplex was
    // seen to call such a polytope infeasible from both bases. An infeasible answer is the projection's
    // claim, which solve() re-checks in exact arithmetic before it reports it.
    glp_scale_prob(lp_, GLP_SF_AUTO);
    glp_std_basis(lp_);
    st = glpk_solve_robust(lp_, parm_, false);
    glp_unscale_prob(lp_);
    if (st != GLP_OPT) return;
    fx = std::abs(glp_get_col_prim(lp_, 1));
    fu = std::abs(glp_get_col_prim(lp_, 2));
  });
  if (!ok) return glpk_error();
  if (st != GLP_OPT) {
    out_.outcome = st == GLP_NOFEAS ? Projection::Outcome::Empty : Projection::Outcome::Failed;
    if (st != GLP_NOFEAS) out_.note = "the LP solver did not finish (feasibility without the stand-in bounds)";
    return Step::Stop;
  }
  const double grown = std::pow(10.0, std::ceil(std::log10(std::max(fx, fu))) + 2.0);
  if (!(grown <= kLargestStandIn) || !(grown > stand_in_)) {
    out_.outcome = Projection::Outcome::Failed;
    out_.note = "the shadow lies beyond (x, u) = 1e15 (no polygon represents it)";
    return Step::Stop;
  }
  if (capped(xhi_)) xhi_ = grown;
  if (capped(ulo_)) ulo_ = -grown;
  if (capped(uhi_)) uhi_ = grown;
  stand_in_ = grown;
  // A coordinate found beyond the old bounds is scaled to order one (its column times s, its bounds over
  // s). It does not make these LPs reliable (on Talos their optima still reached the grown bounds along u
  // where HiGHS's did not): hence project() reports the polygon inexact.
  auto scale_of = [&](double f) { return f > in_.stand_in ? std::pow(10.0, std::round(std::log10(f))) : 1.0; };
  sx_ = scale_of(fx);
  su_ = scale_of(fu);
  std::vector<int>& ia = self_.ia_;
  std::vector<double>& ar = self_.ar_;
  for (int j = 0; j < 2; ++j) {
    const double sc = j == 0 ? sx_ : su_;
    if (sc == 1.0) continue;
    ia.assign(1, 0);
    ar.assign(1, 0.0);
    for (Eigen::Index r = 0; r < in_.A.rows(); ++r)
      if (in_.A(r, j) != 0.0) {
        ia.push_back(static_cast<int>(r) + 1);
        ar.push_back(in_.A(r, j) * sc);
      }
    if (!guarded([&] { glp_set_mat_col(lp_, j + 1, static_cast<int>(ar.size()) - 1, ia.data(), ar.data()); }))
      return glpk_error();
  }
  const bool bounds_set = guarded([&] {
    glpk_set_bounds(lp_, false, 1, xlo_ / sx_, xhi_ / sx_);
    glpk_set_bounds(lp_, false, 2, ulo_ / su_, uhi_ / su_);
  });
  return bounds_set ? Step::Ok : glpk_error();
}

// A vertex on a stand-in bound is not part of the polygon's extent.
bool PolytopeProjector::Run::real(const Vertex& p, bool along_x) const {
  const double v = along_x ? p.x : p.y, lo = along_x ? xlo_ : ulo_, hi = along_x ? xhi_ : uhi_;
  return !((v >= hi && is_stand_in(hi)) || (v <= lo && is_stand_in(lo)));
}

// The hull's size: the larger of its x and u extents, vertices on stand-in bounds left out.
double PolytopeProjector::Run::size_of() const {
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY, mag = 0.0;
  for (int i : hull_) {
    const Vertex& p = points_[static_cast<size_t>(i)];
    if (real(p, true)) xlo = std::min(xlo, p.x), xhi = std::max(xhi, p.x), mag = std::max(mag, std::abs(p.x));
    if (real(p, false)) ylo = std::min(ylo, p.y), yhi = std::max(yhi, p.y), mag = std::max(mag, std::abs(p.y));
  }
  double size = 0.0;
  if (xhi >= xlo) size = std::max(size, xhi - xlo);
  if (yhi >= ylo) size = std::max(size, yhi - ylo);
  // A polygon that is (nearly) a point still needs a floor above the LPs' rounding: a thousandth of its
  // distance from the origin, or an absolute 1e-14 at the origin.
  return std::max(size, 1e-3 * mag);
}

void PolytopeProjector::Run::hull_changed() {
  convex_hull(points_, hull_);
  const double size = size_of();
  tol_ = std::max(relative_tolerance_ * size, 1e-14);
  approx_ = approximation_ * size;
}

// The polygon: the hull's vertices and edges (an inner set, certified when complete); with a focus, the
// outer polygon as the half-planes and the hull's edges beside them.
void PolytopeProjector::Run::polygon() {
  out_.tolerance = std::max(tol_, approx_);
  for (int i : hull_) out_.vertices.push_back(points_[static_cast<size_t>(i)]);
  const size_t h = out_.vertices.size();
  auto line = [&](double nx, double nu, const Vertex& on) {
    const double len = std::hypot(nx, nu);
    nx /= len;
    nu /= len;
    double c = nx * on.x + nu * on.y;
    for (const Vertex& v : out_.vertices) c = std::max(c, nx * v.x + nu * v.y);  // never cut a hull vertex
    return Line{nx, nu, c, 0};
  };
  std::vector<Line>& edges = focus_ ? out_.hull : out_.halfplanes;
  auto push = [&](double nx, double nu, const Vertex& on, int from, int to) {
    auto it = certified_.find({from, to});
    const bool certified = it != certified_.end();
    if (focus_) out_.hull_certified.push_back(certified ? 1 : 0);
    else out_.binding.push_back(certified ? it->second : kBindingUnknown);
    edges.push_back(line(nx, nu, on));
    edges.back().id = static_cast<int>(edges.size()) - 1;
  };
  if (h == 1) {
    const Vertex& p = out_.vertices[0];
    push(1, 0, p, -1, -1);
    push(0, 1, p, -1, -1);
    push(-1, 0, p, -1, -1);
    push(0, -1, p, -1, -1);
  } else if (h == 2) {  // a segment: its two sides and its two ends, counter-clockwise
    const Vertex &a = out_.vertices[0], &b = out_.vertices[1];
    const int i = hull_[0], j = hull_[1];
    push(b.y - a.y, -(b.x - a.x), a, i, j);
    push(b.x - a.x, b.y - a.y, b, j, j);
    push(a.y - b.y, -(a.x - b.x), b, j, i);
    push(a.x - b.x, a.y - b.y, a, i, i);
  } else {
    for (size_t e = 0; e < h; ++e) {
      const Vertex &a = out_.vertices[e], &b = out_.vertices[(e + 1) % h];
      push(b.y - a.y, -(b.x - a.x), a, hull_[e], hull_[(e + 1) % h]);
    }
  }
  if (focus_) outer_polygon();
  out_.outcome = Projection::Outcome::Polygon;
}

// With a focus: every LP optimum p along v gives v·z <= v·p, and every certified edge n·z <= its offset (to
// the tolerance): their intersection holds the whole shadow. Where the hull is certified it is exact. The
// certified edges come first (their rows are named by what binds them, and the first row of a name gets it
// plain); a support line at a hull vertex whose two edges are certified is left out: those edges imply it
// (its direction lies between their normals, and the shadow there is the hull's).
void PolytopeProjector::Run::outer_polygon() {
  auto push = [&](double nx, double nu, double c, int code) {
    for (const Vertex& v : out_.vertices) c = std::max(c, nx * v.x + nu * v.y);
    out_.halfplanes.push_back({nx, nu, c, static_cast<int>(out_.halfplanes.size())});
    out_.binding.push_back(code);
  };
  for (const auto& [d, code] : certified_lines_) push(d.nx, d.nu, d.offset, code);
  const size_t h = hull_.size();
  for (size_t i = 0; i < points_.size(); ++i) {
    if (h >= 3) {
      const auto at = std::find(hull_.begin(), hull_.end(), static_cast<int>(i));
      if (at != hull_.end()) {
        const size_t e = static_cast<size_t>(at - hull_.begin());
        const int prev = hull_[(e + h - 1) % h], next = hull_[(e + 1) % h];
        if (certified_.count({prev, static_cast<int>(i)}) && certified_.count({static_cast<int>(i), next})) continue;
      }
    }
    const Vertex &d = support_[i], &p = points_[i];
    push(d.x, d.y, d.x * p.x + d.y * p.y, support_binding_[i]);
  }
}

}  // namespace pathpace::detail
