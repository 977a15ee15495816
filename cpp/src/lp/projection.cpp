#include "lp/projection.hpp"

#include "lp/glpk_util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <glpk.h>

namespace pathpace::detail {

namespace {

double cross(const Vertex& o, const Vertex& a, const Vertex& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

}  // namespace

// An optimal basis of eq. (19) stays optimal for every direction v in which its reduced costs keep their
// signs; they are linear in v: d_j(v) = v_x A_j + v_u B_j over the nonbasic variables j (A_j = [j = x] +
// α_xj, B_j = [j = u] + α_uj, α the tableau rows of x and u, x_B = Σ α x_N). If an edge's outward normal
// keeps the basis of one of its endpoints dual feasible (GLPK's own optimality test, with a stricter
// tolerance), that endpoint is an optimum along the normal: the edge's LP, started from that basis,
// would stop there without a pivot and certify the edge. The test replaces that LP (one LP per vertex
// instead of one per vertex and one per edge), and the same reduced costs give binding()'s duals.
struct PolytopeProjector::Ranging {
  std::vector<int> var;            // GLPK variable: 1..rows (auxiliary), rows + 1.. (structural)
  std::vector<signed char> stat;   // GLP_NL, GLP_NU, GLP_NF, GLP_NS
  std::vector<double> A, B;
};

void convex_hull(const std::vector<Vertex>& points, std::vector<int>& order) {
  std::vector<int> idx(points.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  std::sort(idx.begin(), idx.end(), [&](int i, int j) {
    const Vertex &p = points[static_cast<size_t>(i)], &q = points[static_cast<size_t>(j)];
    return p.x < q.x || (p.x == q.x && p.y < q.y);
  });
  idx.erase(std::unique(idx.begin(), idx.end(),
                        [&](int i, int j) {
                          const Vertex &p = points[static_cast<size_t>(i)], &q = points[static_cast<size_t>(j)];
                          return p.x == q.x && p.y == q.y;
                        }),
            idx.end());
  order.clear();
  if (idx.size() <= 2) {
    order = idx;
    return;
  }
  // Lower hull left to right, then upper hull right to left; a turn that is not strictly
  // counter-clockwise drops the middle point.
  std::vector<int> h(2 * idx.size());
  size_t k = 0;
  auto P = [&](int i) -> const Vertex& { return points[static_cast<size_t>(i)]; };
  for (size_t i = 0; i < idx.size(); ++i) {
    while (k >= 2 && cross(P(h[k - 2]), P(h[k - 1]), P(idx[i])) <= 0) --k;
    h[k++] = idx[i];
  }
  for (size_t i = idx.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(P(h[k - 2]), P(h[k - 1]), P(idx[i])) <= 0) --k;
    h[k++] = idx[i];
  }
  h.resize(k - 1);  // the last point is the first
  order = std::move(h);
}

Projection project_polytope(const PolytopeLp& in, double relative_tolerance, int max_lps, double approximation) {
  PolytopeProjector p;
  return p.project(in, relative_tolerance, max_lps, approximation);
}

PolytopeProjector::~PolytopeProjector() = default;

int PolytopeProjector::load(const PolytopeLp& in) {
  const int rows = static_cast<int>(in.A.rows()), cols = static_cast<int>(in.A.cols());
  // A problem freed by a GLPK error (get() == nullptr) is created again, cold.
  const bool warm = lp_.get() != nullptr && rows == rows_ && cols == cols_;
  if (!warm) {
    rows_ = cols_ = -1;
    if (!lp_.create()) return -1;
  }
  dense_triplets(in.A, ia_, ja_, ar_);
  glp_prob* lp = lp_.get();
  const bool ok = guarded([&] {
    if (!warm) {
      glp_set_obj_dir(lp, GLP_MAX);
      if (rows > 0) glp_add_rows(lp, rows);
      if (cols > 0) glp_add_cols(lp, cols);
    }
    for (int i = 0; i < rows; ++i) glpk_set_bounds(lp, true, i + 1, in.row_lo[i], in.row_hi[i]);
    for (int j = 0; j < cols; ++j) glpk_set_bounds(lp, false, j + 1, in.col_lo[j], in.col_hi[j]);
    glpk_load_triplets(lp, ia_, ja_, ar_);
    // A new problem starts from an advanced basis; a reloaded one keeps the previous point's statuses.
    if (!warm) glp_adv_basis(lp, 0);
  });
  if (!ok) return -1;
  rows_ = rows;
  cols_ = cols;
  return warm ? 1 : 0;
}

namespace {

// False after a GLPK error (parm is then not set).
bool simplex_parameters(int rows, int cols, glp_smcp& parm) {
  if (!guarded([&] { glp_init_smcp(&parm); })) return false;  // it only fills the struct, but it is GLPK
  parm.msg_lev = GLP_MSG_OFF;
  // No scaling, no presolve: GLPK's automatic scaling was seen to make the primal simplex declare small,
  // plainly feasible projection LPs infeasible (rows of torque balance next to stand-in bounds of 1e6).
  parm.presolve = GLP_OFF;
  // Never a hang: a cycling simplex ends as a failure, and is retried (glpk_solve_robust). A warm
  // solve takes a few dozen pivots, a cold one at most a few times rows + cols.
  parm.it_lim = 10 * (rows + cols) + 100;
  // GLPK's default bound tolerance (1e-7, relative to each bound) lets an optimum lie outside the
  // polytope by more than the 1e-9 of the polygon's size that the projection certifies, and hides
  // vertices of short edges; these small dense LPs solve as reliably at 1e-10.
  parm.tol_bnd = 1e-10;
  parm.tol_dj = 1e-10;
  return true;
}

}  // namespace

int PolytopeProjector::feasible(const PolytopeLp& in, const double* fix) {
  glp_smcp parm;
  if (!simplex_parameters(static_cast<int>(in.A.rows()), static_cast<int>(in.A.cols()), parm) || load(in) < 0) return -1;
  glp_prob* lp = lp_.get();
  int st = -1;
  const bool ok = guarded([&] {
    if (fix) {
      glpk_set_bounds(lp, false, 1, fix[0], fix[0]);
      glpk_set_bounds(lp, false, 2, fix[1], fix[1]);
    }
    glp_set_obj_coef(lp, 1, 0.0);
    glp_set_obj_coef(lp, 2, 0.0);
    st = glpk_solve_robust(lp, parm);
    if (fix) {  // the next projection reloads the bounds anyway; restore them for a warm feasible() too
      glpk_set_bounds(lp, false, 1, in.col_lo[0], in.col_hi[0]);
      glpk_set_bounds(lp, false, 2, in.col_lo[1], in.col_hi[1]);
    }
  });
  if (!ok) return -1;
  return st == GLP_OPT ? 1 : st == GLP_NOFEAS ? 0 : -1;
}

int PolytopeProjector::maximize(const PolytopeLp& in, const Eigen::VectorXd& c, Eigen::VectorXd& z) {
  glp_smcp parm;
  if (!simplex_parameters(static_cast<int>(in.A.rows()), static_cast<int>(in.A.cols()), parm) || load(in) < 0) return -2;
  glp_prob* lp = lp_.get();
  const int cols = cols_;
  z_.resize(static_cast<size_t>(cols));
  double* zp = z_.data();
  const double* cp = c.data();
  int st = -1;
  const bool ok = guarded([&] {
    for (int j = 0; j < cols; ++j) glp_set_obj_coef(lp, j + 1, cp[j]);
    st = glpk_solve_robust(lp, parm);
    if (st == GLP_OPT)
      for (int j = 0; j < cols; ++j) zp[j] = glp_get_col_prim(lp, j + 1);
    for (int j = 0; j < cols; ++j) glp_set_obj_coef(lp, j + 1, 0.0);  // project() sets only x's and u's
  });
  if (!ok) return -2;
  if (st != GLP_OPT) return st == GLP_NOFEAS ? 0 : -1;
  z = Eigen::Map<const Eigen::VectorXd>(z_.data(), cols);
  return 1;
}

Projection PolytopeProjector::project(const PolytopeLp& in, double relative_tolerance, int max_lps, double approximation) {
  Projection out;
  // A GLPK error (guarded() returned false): the problem is gone with the environment; so is the result.
  auto glpk_error = [&out]() {
    out.outcome = Projection::Outcome::Failed;
    out.complete = false;
    out.note = "GLPK error";
    return out;
  };
  // The parameters first: a GLPK error there frees the problem before load() looks at it.
  glp_smcp parm;
  if (!simplex_parameters(static_cast<int>(in.A.rows()), static_cast<int>(in.A.cols()), parm)) return glpk_error();
  const int loaded = load(in);
  if (loaded < 0) return glpk_error();
  const bool warm = loaded == 1;
  glp_prob* lp = lp_.get();
  const int rows = rows_, cols = cols_;

  // eq. (19): max v·(x, u) over the polytope; 1 optimal, 0 infeasible (confirmed exactly), -1 failed.
  // The LP's columns 1 and 2 are x / sx and u / su: scaled only when the shadow lies far beyond the
  // stand-in bounds (below), so that GLPK's unscaled simplex sees values of order one.
  double sx = 1.0, su = 1.0;
  // Warm starts across grid points (sec. IV.C): each LP starts from the final basis of the previous
  // grid point's LP in the nearest direction, if one was within kNear radians, by the dual simplex. That
  // basis is optimal for a nearby polytope and direction, so it is (nearly) dual feasible and a few dual
  // pivots restore primal feasibility; from the basis of the LP just before (another direction) the
  // primal simplex took ~30 pivots per LP on a 60-contact humanoid. Any start gives an optimum, so the
  // polygon does not depend on it (a degenerate optimum may be another point of the same edge).
  // Only for LPs of at least kRestoreColumns columns: a restored basis is refactorised (~ the cost of a
  // few pivots), which made the 8-contact humanoid (66 columns, few pivots per LP) 5-15 % slower and
  // the 60-contact one (482 columns, ~31 pivots per LP) 2.2x faster.
  constexpr int kRestoreColumns = 200;
  const bool same_shape = warm && !previous_.empty() && cols_ >= kRestoreColumns;
  std::vector<char> nonempty_col(static_cast<size_t>(cols_), 0);
  if (same_shape)
    for (int j = 0; j < cols_; ++j) nonempty_col[static_cast<size_t>(j)] = (in.A.col(j).array() != 0.0).any();
  constexpr double kNear = 0.35;
  current_.clear();
  glp_smcp dual = parm;
  dual.meth = GLP_DUALP;
  stat_.resize(static_cast<size_t>(rows + cols));
  // The ranging of the last LP's optimal basis (empty when it is not computed: scaled columns).
  Ranging last_range;
  // From kRangingColumns columns on: below, an LP is a few pivots on a tiny basis and costs about what
  // the two tableau rows do (and the rod of test_continuous, 6 columns, keeps its LP sequence).
  constexpr int kRangingColumns = 30;
  // The tableau rows of x and u (1-based over every variable, GLPK's numbering), read inside the LP's
  // guarded call into these buffers sized here (glpk_guard.hpp's rule 1); the Ranging is built after it.
  const int total = rows + cols;
  tab_ind_.resize(static_cast<size_t>(total) + 1);
  tab_val_.resize(static_cast<size_t>(total) + 1);
  tab_x_.resize(static_cast<size_t>(total) + 1);
  tab_u_.resize(static_cast<size_t>(total) + 1);
  auto range_basis = [&](Ranging& rg, bool computed) {
    rg = Ranging();
    if (!computed) return;
    for (int k = 1; k <= total; ++k) {
      const signed char st = stat_[static_cast<size_t>(k - 1)];
      if (st == GLP_BS) continue;
      rg.var.push_back(k);
      rg.stat.push_back(st);
      rg.A.push_back(tab_x_[static_cast<size_t>(k)] + (k == rows + 1 ? 1.0 : 0.0));
      rg.B.push_back(tab_u_[static_cast<size_t>(k)] + (k == rows + 2 ? 1.0 : 0.0));
    }
  };
  // The dense simplex (dense_simplex.hpp) within the grid point: an LP starts from the optimal basis of
  // the support point `start` (an edge's endpoint: primal feasible, nearly optimal along the edge's
  // normal); GLPK solves the first LP of a point and any LP the dense simplex gives up on, and its basis
  // is then taken over. Only on the LP's own unscaled bounds (not after the stand-in bounds grew).
  const bool use_dense = dense && cols >= kRangingColumns;
  if (use_dense) dense_.load(in);
  // Per support point: its optimal basis (stat), factorised (head, inv) the first time an LP starts from it.
  std::vector<DenseSimplex::State> states;
  std::vector<Vertex> support;  // per support point: the (unit) direction of the LP that found it
  DenseSimplex::State last_state;
  bool last_dense = false;  // the last LP was solved by the dense simplex (binding() reads it)
  bool bounds_grown = false;
  auto dense_ok = [&] { return use_dense && sx == 1.0 && su == 1.0 && !bounds_grown; };
  auto extremize = [&](double vx, double vu, Vertex& p, int start_point) -> int {  // also -2: a GLPK error
    ++out.lp_solves;
    const double angle = std::atan2(vu, vx);
    last_dense = false;
    last_state = DenseSimplex::State();
    // Only from a support point whose direction is within kDenseAngle of this one: farther (a coarse
    // polygon, projection_tolerance) the primal simplex from it takes many pivots, and GLPK's dual simplex
    // from the previous grid point's basis in this direction (below) is the better start.
    constexpr double kDenseAngle = 0.25;
    DenseSimplex::State* origin = nullptr;
    if (dense_ok() && start_point >= 0) {
      const Vertex& w = support[static_cast<size_t>(start_point)];
      DenseSimplex::State& st = states[static_cast<size_t>(start_point)];
      if (w.x * vx + w.y * vu >= std::cos(kDenseAngle) && !st.stat.empty()) origin = &st;
    }
    if (origin && origin->head.empty()) {  // factorised on first use
      if (dense_.set_basis(origin->stat.data())) *origin = dense_.state();
      else origin->stat.clear(), origin = nullptr;
    }
    if (origin) {
      dense_.restore(*origin);
      if (dense_.maximize(vx, vu) == 1) {
        ++out.dense_solves;
        last_dense = true;
        p = {dense_.x(), dense_.u()};
        if (ranging) dense_.tableau_xu(tab_x_.data(), tab_u_.data());
        last_state = dense_.take();  // moved, not copied (B^-1 is rows² doubles): the next LP restores
        std::copy(last_state.stat.begin(), last_state.stat.end(), stat_.begin());
        const bool record = cols >= kRestoreColumns;
        range_basis(last_range, ranging);
        if (record) current_.push_back({angle, stat_});
        return 1;
      }
      ++out.dense_fallbacks;
    }
    const Basis* from = nullptr;
    if (same_shape) {
      double best = kNear;
      for (const Basis& b : previous_) {
        double d = std::abs(b.angle - angle);
        d = std::min(d, 2.0 * M_PI - d);
        if (d < best) best = d, from = &b;
      }
    }
    if (from) {
      // A basic column that is empty in this grid point's matrix (a coefficient rounded to zero) makes
      // the basis singular, which GLPK's factorization was seen to meet with an assertion, not a status.
      for (int j = 0; j < cols && from; ++j)
        if (from->stat[static_cast<size_t>(rows + j)] == GLP_BS && !nonempty_col[static_cast<size_t>(j)]) from = nullptr;
    }
    const signed char* start = from ? from->stat.data() : nullptr;
    const signed char* fallback = from ? (current_.empty() ? previous_.back() : current_.back()).stat.data() : nullptr;
    const bool record = cols >= kRestoreColumns;  // no basis is restored below this size: none is recorded
    // Ranging only on unscaled columns (its reduced costs are in the LP's own units).
    const bool range = ranging && cols >= kRangingColumns && sx == 1.0 && su == 1.0;
    signed char* stat = stat_.data();
    int* tab_ind = tab_ind_.data();
    double *tab_val = tab_val_.data(), *tab_x = tab_x_.data(), *tab_u = tab_u_.data();
    int st = -1;
    bool ranged = false;
    double px = 0.0, pu = 0.0;
    const bool ok = guarded([&] {
      glp_set_obj_coef(lp, 1, vx * sx);
      glp_set_obj_coef(lp, 2, vu * su);
      auto restore = [&](const signed char* b) {
        for (int i = 0; i < rows; ++i) glp_set_row_stat(lp, i + 1, b[i]);
        for (int j = 0; j < cols; ++j) glp_set_col_stat(lp, j + 1, b[rows + j]);
      };
      const glp_smcp* method = &parm;
      if (start) {
        restore(start);
        // Dual feasible (to the simplex's tolerance): the dual simplex. Otherwise (a degenerate vertex whose
        // reduced costs changed sign) back to the basis of the LP just before (primal feasible within a grid
        // point) and the primal simplex: from the restored basis it was seen to take 300-400 pivots.
        if (glp_warm_up(lp) == 0 && glp_get_dual_stat(lp) == GLP_FEAS) method = &dual;
        else restore(fallback);
      }
      st = glpk_solve_robust(lp, *method, false);
      if (st != GLP_OPT) return;
      px = glp_get_col_prim(lp, 1);
      pu = glp_get_col_prim(lp, 2);
      if (!record && !range) return;
      for (int i = 0; i < rows; ++i) stat[i] = static_cast<signed char>(glp_get_row_stat(lp, i + 1));
      for (int j = 0; j < cols; ++j) stat[rows + j] = static_cast<signed char>(glp_get_col_stat(lp, j + 1));
      if (!range || !glp_bf_exists(lp)) return;
      // The tableau rows of x and u (zero where that column is nonbasic: its reduced cost is then v's own).
      auto tab_row = [&](int col, double* out) {
        for (int k = 0; k <= total; ++k) out[k] = 0.0;
        if (stat[rows + col - 1] != GLP_BS) return;
        const int len = glp_eval_tab_row(lp, rows + col, tab_ind, tab_val);
        for (int t = 1; t <= len; ++t) out[tab_ind[t]] = tab_val[t];
      };
      tab_row(1, tab_x);
      tab_row(2, tab_u);
      ranged = true;
    });
    if (!ok) return -2;
    if (st != GLP_OPT) return st == GLP_NOFEAS ? 0 : -1;
    p = {sx * px, su * pu};
    range_basis(last_range, ranged);
    // GLPK's optimal basis, for the dense simplex's next LPs (stat_ is filled when range or record is).
    if (dense_ok() && (record || range)) last_state.stat = stat_;
    if (record) current_.push_back({angle, stat_});
    return 1;
  };

  std::vector<Vertex> points;  // every support point found
  std::vector<Ranging> ranges;  // and its LP's ranging
  // The stand-in bounds on x and u (those at least in.stand_in in magnitude): the shadow is that of the
  // polytope without them, which they must not cut. Grown below when they hide all of it.
  double xlo = in.col_lo[0], xhi = in.col_hi[0], ulo = in.col_lo[1], uhi = in.col_hi[1];
  double stand_in = in.stand_in;
  auto is_stand_in = [&](double b) { return std::abs(b) >= stand_in; };
  auto capped = [&](double b) { return std::isfinite(b) && is_stand_in(b); };  // a bound the LPs see
  // Initial directions: the vertices of an equilateral triangle (sec. IV.C). They positively span the
  // plane, so a shadow whose three support points coincide is that point. An LP that fails here keeps
  // the support points found so far (an inner set, reported incomplete).
  for (int i = 0; i < 3; ++i) {
    const double ang = 2.0 * M_PI * i / 3.0;
    Vertex p;
    const int r = extremize(std::cos(ang), std::sin(ang), p, static_cast<int>(points.size()) - 1);
    ++out.by_cause.initial;
    if (r == -2) return glpk_error();
    if (r == 0 && i == 0 && (capped(xhi) || capped(ulo) || capped(uhi))) {
      // Infeasible with the stand-in bounds: is it without them? A polytope whose shadow lies only beyond
      // them (a grid point where b ~ 1e-8, so that s̈ ~ 1e10 would be needed) is not empty, and calling it
      // empty contradicts solve()'s re-check on the full polytope. One feasibility LP without them; if
      // feasible, the bounds grow past its point (x, u) and the projection starts again.
      const double x_hi = capped(xhi) ? INFINITY : xhi, u_lo = capped(ulo) ? -INFINITY : ulo,
                   u_hi = capped(uhi) ? INFINITY : uhi;
      ++out.lp_solves;
      ++out.by_cause.cap_growth;
      int st = -1;
      double fx = 0.0, fu = 0.0;
      const bool ok = guarded([&] {
        glp_set_obj_coef(lp, 1, 0.0);
        glp_set_obj_coef(lp, 2, 0.0);
        glpk_set_bounds(lp, false, 1, xlo, x_hi);
        glpk_set_bounds(lp, false, 2, u_lo, u_hi);
        // With GLPK's scaling, for this LP only: with b ~ 1e-8 against forces ~ 1e2 the unscaled simplex
        // was seen to call such a polytope infeasible from both bases (exact arithmetic gets it right too,
        // but costs ~30 ms per truly empty point). An infeasible answer is the projection's claim, which
        // solve() re-checks in exact arithmetic before it reports it.
        glp_scale_prob(lp, GLP_SF_AUTO);
        glp_std_basis(lp);
        st = glpk_solve_robust(lp, parm, false);
        glp_unscale_prob(lp);
        if (st != GLP_OPT) return;
        fx = std::abs(glp_get_col_prim(lp, 1));
        fu = std::abs(glp_get_col_prim(lp, 2));
      });
      if (!ok) return glpk_error();
      if (st != GLP_OPT) {
        out.outcome = st == GLP_NOFEAS ? Projection::Outcome::Empty : Projection::Outcome::Failed;
        if (st != GLP_NOFEAS) out.note = "the LP solver did not finish (feasibility without the stand-in bounds)";
        return out;
      }
      const double grown = std::pow(10.0, std::ceil(std::log10(std::max(fx, fu))) + 2.0);
      if (!(grown <= kLargestStandIn) || !(grown > stand_in)) {
        out.outcome = Projection::Outcome::Failed;
        out.note = "the shadow lies beyond (x, u) = 1e15 (no polygon represents it)";
        return out;
      }
      if (capped(xhi)) xhi = grown;
      if (capped(ulo)) ulo = -grown;
      if (capped(uhi)) uhi = grown;
      stand_in = grown;
      bounds_grown = true;
      // A coordinate found beyond the old bounds is scaled to order one (its column times s, its bounds
      // over s), so that GLPK's unscaled simplex sees values of order one. It does not make these LPs
      // reliable (on Talos its optima still reached the grown bounds along u where HiGHS's did not):
      // hence the polygon is reported inexact below.
      auto scale_of = [&](double f) { return f > in.stand_in ? std::pow(10.0, std::round(std::log10(f))) : 1.0; };
      sx = scale_of(fx);
      su = scale_of(fu);
      for (int j = 0; j < 2; ++j) {
        const double sc = j == 0 ? sx : su;
        if (sc == 1.0) continue;
        ia_.assign(1, 0);
        ar_.assign(1, 0.0);
        for (Eigen::Index r = 0; r < in.A.rows(); ++r)
          if (in.A(r, j) != 0.0) {
            ia_.push_back(static_cast<int>(r) + 1);
            ar_.push_back(in.A(r, j) * sc);
          }
        if (!guarded([&] { glp_set_mat_col(lp, j + 1, static_cast<int>(ar_.size()) - 1, ia_.data(), ar_.data()); }))
          return glpk_error();
      }
      const bool bounds_set = guarded([&] {
        glpk_set_bounds(lp, false, 1, xlo / sx, xhi / sx);
        glpk_set_bounds(lp, false, 2, ulo / su, uhi / su);
      });
      if (!bounds_set) return glpk_error();
      i = -1;  // again, from the feasible basis just found
      continue;
    }
    if (r <= 0) {
      if (!points.empty()) {  // an LP failed after a feasible one: keep what was found
        out.complete = false;
        out.note = "the LP solver did not finish (initial direction " + std::to_string(i) + ")";
        break;
      }
      out.outcome = r == 0 ? Projection::Outcome::Empty : Projection::Outcome::Failed;
      if (r < 0) out.note = "the LP solver did not finish (initial direction " + std::to_string(i) + ")";
      return out;
    }
    points.push_back(p);
    ranges.push_back(std::move(last_range));
    support.push_back({std::cos(ang), std::sin(ang)});
    states.push_back(std::move(last_state));
  }
  out.stand_in = stand_in;
  // A shadow found only beyond the stand-in bounds is not called exact: there b·u ~ 1e2 with b ~ 1e-8 (the
  // rounding residue of a path derivative), and the LPs' optima were seen to differ from HiGHS's by
  // orders of magnitude along u. What matters is that it is not empty (the status then comes from
  // reachability, which such an s̈ cannot satisfy, not from a false "no forces balance the robot").
  const bool grown_bounds = stand_in != in.stand_in;
  const bool initial_complete = points.size() == 3;

  // A vertex on a stand-in bound is not part of the polygon's extent.
  auto real = [&](const Vertex& p, bool along_x) {
    const double v = along_x ? p.x : p.y, lo = along_x ? xlo : ulo, hi = along_x ? xhi : uhi;
    return !((v >= hi && is_stand_in(hi)) || (v <= lo && is_stand_in(lo)));
  };
  auto size_of = [&](const std::vector<int>& hull) {
    double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY, mag = 0.0;
    for (int i : hull) {
      const Vertex& p = points[static_cast<size_t>(i)];
      if (real(p, true)) xlo = std::min(xlo, p.x), xhi = std::max(xhi, p.x), mag = std::max(mag, std::abs(p.x));
      if (real(p, false)) ylo = std::min(ylo, p.y), yhi = std::max(yhi, p.y), mag = std::max(mag, std::abs(p.y));
    }
    double size = 0.0;
    if (xhi >= xlo) size = std::max(size, xhi - xlo);
    if (yhi >= ylo) size = std::max(size, yhi - ylo);
    // A polygon that is (nearly) a point still needs a floor above the LPs' rounding: a thousandth of
    // its distance from the origin, or an absolute 1e-14 at the origin.
    return std::max(size, 1e-3 * mag);
  };
  auto tolerance = [&](const std::vector<int>& hull) {
    return std::max(relative_tolerance * size_of(hull), 1e-14);
  };
  // projection_tolerance: every LP optimum p found along v gives the outer half-plane v·z <= v·p of the
  // shadow. Beyond an edge (a, b) with normal n, those of a and b (v_a before n before v_b, counter-
  // clockwise) leave the triangle a, apex, b; in every direction d between v_a and v_b the shadow's
  // support exceeds the hull's by at most d·(apex - a) (or - b) <= the apex's height above the edge.
  // An edge whose apex lies within `approx` of it is final: the hull stays (an inner set, conservative).
  double approx = 0.0;
  auto within_approximation = [&](int from, int to, double nx, double nu, double offset) {
    if (!(approx > 0.0) || from == to) return false;
    const Vertex &da = support[static_cast<size_t>(from)], &db = support[static_cast<size_t>(to)];
    const double det = da.x * db.y - da.y * db.x;
    if (!(da.x * nu - da.y * nx > 0.0) || !(nx * db.y - nu * db.x > 0.0) || !(det > 0.0)) return false;
    const Vertex &a = points[static_cast<size_t>(from)], &b = points[static_cast<size_t>(to)];
    const double ra = da.x * a.x + da.y * a.y, rb = db.x * b.x + db.y * b.y;
    const double px = (ra * db.y - rb * da.y) / det, pu = (da.x * rb - db.x * ra) / det;
    return nx * px + nu * pu - offset <= approx;
  };

  // Certified directions, keyed by the hull edge (from, to) that produced them; (i, i) is the end
  // direction beyond point i of a hull that is a segment. The value: what binds there (see binding()).
  std::map<std::pair<int, int>, int> certified;
  // The constraint that holds the shadow at an edge: at the certifying LP's optimum, the inequality row or
  // column bound with the largest dual (a row's dual per unit of its normalised row), with its side.
  Eigen::VectorXd row_norm = in.A.rowwise().norm();
  const double* norm = row_norm.data();
  auto binding = [&](int& code) {  // false: a GLPK error
    code = kBindingUnknown;
    if (last_dense) {  // the same rule on the dense simplex's statuses and reduced costs
      const std::vector<signed char>& st = last_state.stat;
      double best = 0.0;
      for (int k = 0; k < rows + cols; ++k) {
        if (st[static_cast<size_t>(k)] == GLP_BS) continue;
        if (k < rows && (st[static_cast<size_t>(k)] == GLP_NS || in.row_lo[k] == in.row_hi[k])) continue;
        const double w = std::abs(dense_.reduced_cost(k)) * (k < rows ? norm[k] : 1.0);
        if (w > best) best = w, code = k < rows ? 2 * k + (st[static_cast<size_t>(k)] == GLP_NU ? 1 : 0) : -(k - rows + 1);
      }
      return true;
    }
    return guarded([&] {
      double best = 0.0;
      for (int i = 0; i < rows; ++i) {
        const int st = glp_get_row_stat(lp, i + 1);
        // An equality (e.g. Newton's law on an unactuated base) is structure, not a limit one could relax.
        if (st == GLP_BS || st == GLP_NS || in.row_lo[i] == in.row_hi[i]) continue;
        const double w = std::abs(glp_get_row_dual(lp, i + 1)) * norm[i];
        if (w > best) {
          best = w;
          code = 2 * i + (st == GLP_NU ? 1 : 0);
        }
      }
      for (int j = 0; j < cols; ++j) {
        if (glp_get_col_stat(lp, j + 1) == GLP_BS) continue;
        const double w = std::abs(glp_get_col_dual(lp, j + 1));
        if (w > best) {
          best = w;
          code = -(j + 1);
        }
      }
    });
  };
  // Ranging's certificate (see Ranging): the basis of rg is optimal along (nx, nu), to 1e-11 in every
  // reduced cost (GLPK stops at tol_dj = 1e-10); `code` is then what binding() would say there.
  auto range_certifies = [&](const Ranging& rg, double nx, double nu, int& code) {
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
        if (rg.stat[t] == GLP_NS || in.row_lo[i] == in.row_hi[i]) continue;
        if (d * row_norm[i] > best) best = d * row_norm[i], code = 2 * i + (rg.stat[t] == GLP_NU ? 1 : 0);
      } else if (d > best) {
        best = d;
        code = -(k - rows_);
      }
    }
    return true;
  };
  std::vector<int> hull;
  struct Pending {
    int from, to;
    double nx, nu, offset;
  };
  std::vector<Pending> pending;
  auto directions = [&]() {
    pending.clear();
    const size_t h = hull.size();
    auto add = [&](int from, int to, double nx, double nu) {
      if (certified.count({from, to}) != 0) return;
      const double len = std::hypot(nx, nu);
      if (!(len > 0.0)) return;
      nx /= len;
      nu /= len;
      // The hull's own support value in this direction: attained at the edge's ends (a convex hull).
      const Vertex &a = points[static_cast<size_t>(from)], &b = points[static_cast<size_t>(to)];
      pending.push_back({from, to, nx, nu, std::max(nx * a.x + nu * a.y, nx * b.x + nu * b.y)});
    };
    if (h == 1) return;  // three support points coincide: the shadow is that point
    for (size_t e = 0; e < h; ++e) {
      const int i = hull[e], j = hull[(e + 1) % h];
      const Vertex &a = points[static_cast<size_t>(i)], &b = points[static_cast<size_t>(j)];
      add(i, j, b.y - a.y, -(b.x - a.x));  // outward normal of a counter-clockwise edge
    }
    if (h == 2) {  // a segment: its two ends too
      const Vertex &a = points[static_cast<size_t>(hull[0])], &b = points[static_cast<size_t>(hull[1])];
      add(hull[0], hull[0], a.x - b.x, a.y - b.y);
      add(hull[1], hull[1], b.x - a.x, b.y - a.y);
    }
  };

  convex_hull(points, hull);
  out.complete = initial_complete;
  double tol = tolerance(hull);
  approx = approximation * size_of(hull);
  while (out.complete) {
    directions();
    if (pending.empty()) break;
    bool grew = false;
    for (const Pending& d : pending) {
      int code = kBindingUnknown;
      if (range_certifies(ranges[static_cast<size_t>(d.from)], d.nx, d.nu, code) ||
          range_certifies(ranges[static_cast<size_t>(d.to)], d.nx, d.nu, code)) {
        ++out.ranged_certificates;
        certified[{d.from, d.to}] = code;
        continue;
      }
      if (within_approximation(d.from, d.to, d.nx, d.nu, d.offset)) {
        ++out.approximate_edges;
        certified[{d.from, d.to}] = kBindingUnknown;  // no LP along it: what binds there is not known
        continue;
      }
      if (out.lp_solves >= max_lps) {
        out.complete = false;
        out.note = "LP budget (" + std::to_string(max_lps) + ") ran out with " + std::to_string(pending.size()) +
                   " edges not certified";
        break;
      }
      Vertex q;
      // From the endpoint whose support direction is nearer the edge's normal.
      const Vertex &sa = support[static_cast<size_t>(d.from)], &sb = support[static_cast<size_t>(d.to)];
      const int start = sa.x * d.nx + sa.y * d.nu >= sb.x * d.nx + sb.y * d.nu ? d.from : d.to;
      const int r = extremize(d.nx, d.nu, q, start);
      if (r != 1) ++out.by_cause.vertex;
      if (r == -2) return glpk_error();
      if (r != 1) {
        // The polytope was non-empty three LPs ago: an 'infeasible' here is a solver failure too.
        out.complete = false;
        out.note = "the LP solver did not finish after " + std::to_string(out.lp_solves) + " LPs";
        break;
      }
      if (d.nx * q.x + d.nu * q.y <= d.offset + tol) {
        ++out.by_cause.certificate;
        int code = kBindingUnknown;
        if (!binding(code)) return glpk_error();
        certified[{d.from, d.to}] = code;  // nothing of the shadow beyond this edge
      } else {
        ++out.by_cause.vertex;
        points.push_back(q);  // strictly outside the hull by more than the tolerance
        ranges.push_back(std::move(last_range));
        support.push_back({d.nx, d.nu});
        states.push_back(std::move(last_state));
        grew = true;
        break;  // the hull changes: recompute it and its uncertified edges
      }
    }
    if (!out.complete) break;
    if (grew) {
      convex_hull(points, hull);
      tol = tolerance(hull);
      approx = approximation * size_of(hull);
    }
  }
  if (grown_bounds && out.complete) {
    out.complete = false;
    out.note = "the shadow lies only beyond the stand-in bounds (ill-conditioned LPs there)";
  }

  // The polygon: the hull's vertices and edges (an inner set, certified when complete).
  out.tolerance = std::max(tol, approx);
  for (int i : hull) out.vertices.push_back(points[static_cast<size_t>(i)]);
  const size_t h = out.vertices.size();
  auto push = [&](double nx, double nu, const Vertex& on, int from, int to) {
    auto it = certified.find({from, to});
    out.binding.push_back(it == certified.end() ? kBindingUnknown : it->second);
    const double len = std::hypot(nx, nu);
    nx /= len;
    nu /= len;
    double c = nx * on.x + nu * on.y;
    for (const Vertex& v : out.vertices) c = std::max(c, nx * v.x + nu * v.y);  // never cut a hull vertex
    out.halfplanes.push_back({nx, nu, c, static_cast<int>(out.halfplanes.size())});
  };
  if (h == 1) {
    const Vertex& p = out.vertices[0];
    push(1, 0, p, -1, -1);
    push(0, 1, p, -1, -1);
    push(-1, 0, p, -1, -1);
    push(0, -1, p, -1, -1);
  } else if (h == 2) {  // a segment: its two sides and its two ends, counter-clockwise
    const Vertex &a = out.vertices[0], &b = out.vertices[1];
    const int i = hull[0], j = hull[1];
    push(b.y - a.y, -(b.x - a.x), a, i, j);
    push(b.x - a.x, b.y - a.y, b, j, j);
    push(a.y - b.y, -(a.x - b.x), b, j, i);
    push(a.x - b.x, a.y - b.y, a, i, i);
  } else {
    for (size_t e = 0; e < h; ++e) {
      const Vertex &a = out.vertices[e], &b = out.vertices[(e + 1) % h];
      push(b.y - a.y, -(b.x - a.x), a, hull[e], hull[(e + 1) % h]);
    }
  }
  out.outcome = Projection::Outcome::Polygon;
  std::swap(previous_, current_);
  return out;
}

}  // namespace pathpace::detail
