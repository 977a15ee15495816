#include "solve/reachability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathpace::detail {

namespace {

// p + q where the two nearly cancel is rounding noise, not a coefficient: a 1e-16 entry next to 1 wrecks
// GLPK's row scaling and, divided into a bound, gives an arbitrary number. Exact zero instead.
double cancel(double p, double q) {
  const double r = p + q;
  return std::abs(r) <= 1e-13 * (std::abs(p) + std::abs(q)) ? 0.0 : r;
}

}  // namespace

Chain build_chain(const Eigen::VectorXd& s, const GridSets& sets, const IntervalExtra* extra, const Scale& scale) {
  Chain ch;
  const Eigen::Index n_pts = s.size(), n = n_pts - 1;
  ch.ds = (s.tail(n) - s.head(n)) / scale.s_unit;  // a power of two: exact
  ch.cap = scale.cap;
  ch.x_lo.resize(n_pts);
  ch.x_hi.resize(n_pts);
  ch.x_lo_id.resize(static_cast<size_t>(n_pts));
  ch.x_hi_id.resize(static_cast<size_t>(n_pts));
  for (Eigen::Index k = 0; k < n_pts; ++k) {
    const PointSet& p = sets.points[static_cast<size_t>(k)];
    ch.x_lo[k] = p.x_lo;
    ch.x_hi[k] = p.x_hi;
    ch.x_lo_id[static_cast<size_t>(k)] = p.x_lo_id;
    ch.x_hi_id[static_cast<size_t>(k)] = p.x_hi_id;
  }
  ch.row_offset.resize(static_cast<size_t>(n) + 1);
  ch.coupled_offset.resize(static_cast<size_t>(n));
  ch.row_offset[0] = 0;
  size_t total = 0;
  for (Eigen::Index k = 0; k < n; ++k)
    total += sets.rows(k).size() + sets.rows(k + 1).size() + (extra ? extra->rows[static_cast<size_t>(k)].size() : 0);
  // Written through a pointer into storage sized for every row (see build_point_set: appending row by row
  // reloads and stores the vector's end at every row); the coupling rows of an interval go after its others.
  ch.row_data.resize(total);
  Line* out = ch.row_data.data();
  size_t count = 0;
  std::vector<Line> coupled;
  auto push = [&](double alpha, double beta, double c, int id) {
    if (couples_positively(alpha, beta)) {
      append_line(coupled, alpha, beta, c, id);
      return;
    }
    assign_line(out[count++], alpha, beta, c, id);
  };
  for (Eigen::Index k = 0; k < n; ++k) {
    const double h = 1.0 / (2.0 * ch.ds[k]);
    coupled.clear();
    // eq. (26), forward row at s_k: a θ_k + b (θ_{k+1} - θ_k)/(2Δs_k) <= c
    for (const Line& l : sets.rows(k)) push(cancel(l.a, -l.b * h), l.b * h, l.c, l.id);
    // eq. (26), backward row at s_{k+1}: a θ_{k+1} + b (θ_{k+1} - θ_k)/(2Δs_k) <= c
    for (const Line& l : sets.rows(k + 1)) push(-l.b * h, cancel(l.a, l.b * h), l.c, l.id);
    if (extra)
      for (const Line& l : extra->rows[static_cast<size_t>(k)]) {
        // Rows on θ itself: α x_unit θ̃_k + β x_unit θ̃_{k+1} <= c, exactly, then normalised (a power of two).
        const Line r = power_of_two_normalised({l.a * scale.x_unit, l.b * scale.x_unit, l.c, l.id});
        push(r.a, r.b, r.c, r.id);
      }
    ch.coupled_offset[static_cast<size_t>(k)] = count;
    if (!coupled.empty()) {
      ch.lattice = false;
      for (const Line& l : coupled) out[count++] = l;
    }
    ch.row_offset[static_cast<size_t>(k) + 1] = count;
  }
  ch.row_data.resize(count);
  return ch;
}

bool couples_positively(double alpha, double beta) {
  const double tol = 1e-12 * (std::abs(alpha) + std::abs(beta));
  return alpha > tol && beta > tol;
}

double row_violation(const Line& r, double x, double y) {
  const double ax = r.a * x, by = r.b * y;
  return (ax + by - r.c) / std::max({1.0, std::abs(r.c), std::abs(ax), std::abs(by)});
}

double coupled_violation(const Chain& chain, const Eigen::VectorXd& theta) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < chain.intervals(); ++k)
    for (const Line& r : chain.coupled_rows(k)) worst = raise_violation(worst, r, theta[k], theta[k + 1]);
  return worst;
}

double bound_violation(const Chain& chain, const Eigen::VectorXd& theta) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < theta.size(); ++k) {
    if (theta[k] > chain.x_hi[k]) worst = std::max(worst, (theta[k] - chain.x_hi[k]) / std::max(1.0, std::abs(chain.x_hi[k])));
    if (chain.x_lo[k] > theta[k]) worst = std::max(worst, (chain.x_lo[k] - theta[k]) / std::max(1.0, std::abs(chain.x_lo[k])));
  }
  return worst;
}

double grid_violation(const Chain& chain, const GridSets& sets, const Eigen::VectorXd& theta, Eigen::Index* where) {
  double worst = 0.0;
  Eigen::Index at = -1;
  const Eigen::Index n = chain.intervals();
  for (Eigen::Index k = 0; k <= n; ++k) {
    const double x = theta[k];
    double w = 0.0;
    for (Eigen::Index i : {k - 1, k}) {  // the intervals on either side of point k
      if (i < 0 || i >= n) continue;
      const double h = 1.0 / (2.0 * chain.ds[i]), u = (theta[i + 1] - theta[i]) * h;
      // θ itself resolves s̈ only to ~eps θ / (2Δs): a bound finer than that (a tiny interval of a random
      // grid) cannot be met by any profile of doubles, so the row's scale includes it (a 1e-9 bound at
      // 3.5e-6 of it: 16 eps).
      const double resolution = 3.5e-6 * h * std::max(std::abs(theta[i]), std::abs(theta[i + 1]));
      for (const Line& r : sets.rows(k)) {
        const double ax = r.a * x, bu = r.b * u, d = ax + bu - r.c;
        if (d > 0.0)
          w = std::max(w, d / std::max({1.0, std::abs(r.c), std::abs(ax), std::abs(bu), std::abs(r.b) * resolution}));
      }
    }
    if (x > chain.x_hi[k]) w = std::max(w, (x - chain.x_hi[k]) / std::max(1.0, std::abs(chain.x_hi[k])));
    if (chain.x_lo[k] > x) w = std::max(w, (chain.x_lo[k] - x) / std::max(1.0, std::abs(chain.x_lo[k])));
    if (w > worst) {
      worst = w;
      at = k;
    }
  }
  if (where) *where = at;
  return worst;
}

double exact_feasibility_step(const Chain& chain, const GridSets& sets, Eigen::VectorXd& theta, Eigen::Index* where,
                              double* T_increase, double target) {
  *T_increase = 0.0;
  const double v0 = grid_violation(chain, sets, theta, where);
  const Eigen::Index n = chain.intervals();
  // Boundary speeds other than rest are the user's: a scaled profile would not meet them.
  if (v0 <= target || v0 > 1e-6 || theta[0] != 0.0 || theta[n] != 0.0) return v0;
  double shrink = 4.0 * v0;
  for (int attempt = 0; attempt < 3; ++attempt, shrink *= 2.0) {
    const Eigen::VectorXd scaled = theta / (1.0 + shrink);
    Eigen::Index at = -1;
    const double v = grid_violation(chain, sets, scaled, &at);
    if (v <= target) {
      *T_increase = std::sqrt(1.0 + shrink) - 1.0;  // T ∝ 1 / sqrt(θ) (eq. 25)
      theta = scaled;
      if (where) *where = at;
      return v;
    }
  }
  return v0;
}

namespace {

// Range of y on the polygon's slice at x (x clamped into the polygon's x-range). e[i] is the line through
// v[i - 1] and v[i].
// [x_min, x_max] is the polygon's x-range (its vertices' extremes, as Polygon2d::x_range gives them).
// The bottom of a convex polygon's slice is on an edge whose line bounds y from below (β < 0) or at the
// bottom end of a vertical one (β = 0), the top on one with β > 0 or at a vertical one's top end: y_lo is
// taken from the former only, y_hi from the latter only (at a vertex shared by both kinds, the other kind's
// value could differ by rounding). top_only (the greedy pass) skips the β < 0 edges, about half, and gives
// the same y_hi to the bit; y_lo is then unspecified.
void slice(const Vertex* v, const Line* e, size_t m, double x_min, double x_max, double x, double& y_lo, double& y_hi,
           bool top_only) {
  x = std::clamp(x, x_min, x_max);
  // An edge whose ends differ in x by rounding only is vertical: at such x the whole edge is the slice.
  // (Interpolating along it would turn a 1e-17 error in x into an arbitrary y.) Rounding is relative to
  // each vertex, not to the polygon: an edge from ṡ² = 17 to 8e12 does not reach x = 12 (a tolerance of
  // 1e-12 of the polygon's extent said it did, and the slice's top jumped to 17, s̈ 100x its limit).
  // Accumulated in locals, stored once: through the references (which may alias v and e, for all the
  // compiler knows) every edge stored them.
  const double inf = std::numeric_limits<double>::infinity();
  // by_kind false: every edge for both ends (the rule before the kinds were kept apart), for an end that no
  // edge of its kind reaches, should a degenerate polygon (a sliver left by clipping) have none; a convex
  // polygon always has one, and then this is never run. Per end, so that top_only's y_hi is still the full
  // slice's.
  // reach: how far outside an edge's x-range x may lie and still be sliced on it. First 0: consecutive edges
  // share their vertices, so the edges of each kind tile the x-range exactly, and an edge that reaches x
  // only by a tolerance has its y clamped to its end vertex, which is not on the slice (beside a vertex of
  // two nearly parallel rows, as every interval has on a fine grid, that vertex's y is above the slice's
  // top, and s̈ would break its limit). The tolerance only if no edge contains x.
  auto pass = [&](bool by_kind, double reach, double& lo, double& hi) {
    lo = inf;
    hi = -inf;
    for (size_t i = 0; i < m; ++i) {
      const size_t i1 = i + 1 == m ? 0 : i + 1;  // not (i + 1) % m: an integer division per edge of every slice
      const Line& l = e[i1];
      const bool upper = !by_kind || l.b >= 0.0, lower = !by_kind || l.b <= 0.0;
      if (top_only && !upper) continue;
      const Vertex& p = v[i];
      const Vertex& q = v[i1];
      const double x0 = std::min(p.x, q.x), x1 = std::max(p.x, q.x);
      if (x < x0 - reach * std::abs(x0) || x > x1 + reach * std::abs(x1)) continue;  // the edge does not reach x
      if (x1 - x0 <= 1e-12 * std::max({std::abs(x0), std::abs(x1), 1e-300})) {
        if (lower) lo = std::min({lo, p.y, q.y});
        if (upper) hi = std::max({hi, p.y, q.y});
        continue;
      }
      // Interpolating between the vertices errs by rounding relative to the vertices, the edge's own line
      // (y = (c - a x) / b) by rounding relative to its terms at x: the backward pass keeps speeds that
      // only the start makes unreachable, so an edge may run from ṡ² ~ 1e-2 to 1e13 (limits over many
      // decades), and interpolated at 1e-2 its y was off by 1e13 · 1e-16, s̈ 20x its limit. The smaller
      // error wins; a near-vertical edge (b ~ 0, small p'_j) is still interpolated.
      double y;
      if (std::abs(l.b) * std::max(std::abs(p.y), std::abs(q.y)) > std::abs(l.c) + std::abs(l.a * x)) {
        y = (l.c - l.a * x) / l.b;
      } else {
        const double t = std::clamp((x - p.x) / (q.x - p.x), 0.0, 1.0);
        y = p.y + t * (q.y - p.y);
      }
      y = std::clamp(y, std::min(p.y, q.y), std::max(p.y, q.y));
      if (lower) lo = std::min(lo, y);
      if (upper) hi = std::max(hi, y);
    }
  };
  double lo, hi;
  pass(true, 0.0, lo, hi);
  for (const auto& [by_kind, reach] : {std::pair{true, 1e-12}, std::pair{false, 1e-12}}) {
    if (hi != -inf && (top_only || lo != inf)) break;
    double lo_more, hi_more;
    pass(by_kind, reach, lo_more, hi_more);
    if (hi == -inf) hi = hi_more;
    if (lo == inf) lo = lo_more;
  }
  y_lo = lo;
  y_hi = hi;
}

// The slice of interval k's stored polygon (its own copy, or the relaxed analysis's when they are equal).
void slice(const Reachability& reach, Eigen::Index k, double x, double& y_lo, double& y_hi, bool top_only = false) {
  const size_t i = static_cast<size_t>(k);
  const Reachability& src = reach.base && reach.in_base[i] ? *reach.base : reach;
  const size_t o = src.start[i];
  // The stored K_k is the polygon's x-range (every analysis sets it with x_range from the same polygon).
  slice(src.vertices.data() + o, src.edges.data() + o, src.size[i], src.k_lo[k], src.k_hi[k], x, y_lo, y_hi,
        top_only);
}

void clip_rows(Polygon2d& poly, View<Line> rows) {
  for (const Line& r : rows) {
    poly.clip(r);
    if (poly.empty()) return;
  }
}

// Room for the polygons of n intervals at `per` vertices each, so that storing them does not reallocate
// (each reallocation copies everything stored so far). kPolygonVertices is the mean vertex count of an
// interval's polygon rounded up; more only grows the vectors.
constexpr size_t kPolygonVertices = 8;
void reserve_polygons(Reachability& o, Eigen::Index n, size_t per) {
  o.vertices.clear();
  o.vertices.reserve(static_cast<size_t>(n) * per);
  o.edges.clear();
  o.edges.reserve(static_cast<size_t>(n) * per);
}

// Appends interval k's polygon to the analysis's storage and sets K_k to its x-range.
void store_polygon(Reachability& o, Eigen::Index k, const Polygon2d& p) {
  const View<Vertex> vs = p.vertices();
  const View<Line> es = p.edges();
  o.start[static_cast<size_t>(k)] = o.vertices.size();
  o.size[static_cast<size_t>(k)] = vs.size();
  o.vertices.insert(o.vertices.end(), vs.begin(), vs.end());
  o.edges.insert(o.edges.end(), es.begin(), es.end());
  p.x_range(o.k_lo[k], o.k_hi[k]);
}

void push_unique(std::vector<int>& v, int id) {
  if (id >= 0 && std::find(v.begin(), v.end(), id) == v.end()) v.push_back(id);
}

}  // namespace

void interval_polygon(Polygon2d& poly, double x_lo, double x_hi, double y_lo, double y_hi, View<Line> rows) {
  if (poly.build(x_lo, x_hi, y_lo, y_hi, rows.ptr, rows.n)) return;
  poly.reset(x_lo, x_hi, y_lo, y_hi);
  clip_rows(poly, rows);
}

namespace {

// The greedy pass below caps (none: the greedy maximum), reusing a profile g that was read from the same
// slices: on interval k (k >= 1, and same[k] if given), a pass that arrives at g_k finds the slice g_{k+1} was
// the top of, to the bit, so a cap at or above g_{k+1} gives g_{k+1} again without slicing. (g_0 is the start
// speed, which the pass that made g may have clamped into K_0: interval 0 is always sliced.)
Eigen::VectorXd guided_pass(const Reachability& reach, double theta_begin, const Eigen::VectorXd* caps,
                            const Eigen::VectorXd* g, const std::vector<char>* same) {
  const Eigen::Index n = static_cast<Eigen::Index>(reach.start.size());
  Eigen::VectorXd theta(n + 1);
  theta[0] = theta_begin;
  if (g && g->size() != n + 1) g = nullptr;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (g && k > 0 && theta[k] == (*g)[k] && (!same || (*same)[static_cast<size_t>(k)]) &&
        (!caps || (*caps)[k + 1] >= (*g)[k + 1])) {
      theta[k + 1] = (*g)[k + 1];
      continue;
    }
    double lo, hi;
    slice(reach, k, theta[k], lo, hi, caps == nullptr);
    theta[k + 1] = caps ? std::clamp((*caps)[k + 1], lo, hi) : hi;
  }
  return theta;
}

}  // namespace

Eigen::VectorXd forward_pass(const Reachability& reach, double theta_begin, const Eigen::VectorXd* caps) {
  // A capped pass (the SLP's repair) runs along the analysis's own greedy profile outside its windows.
  return guided_pass(reach, theta_begin, caps, caps && reach.theta_is_greedy ? &reach.theta : nullptr, nullptr);
}

bool has_stopped_interval(const Eigen::VectorXd& theta) {
  for (Eigen::Index k = 0; k + 1 < theta.size(); ++k)
    if (theta[k] + theta[k + 1] <= 0.0) return true;
  return false;
}

Eigen::VectorXd unstopped_profile(const Reachability& reach, double theta_begin) {
  const Eigen::Index n = static_cast<Eigen::Index>(reach.start.size());
  Eigen::VectorXd mid(n + 1);
  mid[0] = theta_begin;
  for (Eigen::Index k = 0; k < n; ++k) {
    double lo, hi;
    slice(reach, k, mid[k], lo, hi);
    mid[k + 1] = 0.5 * (lo + hi);
  }
  mid[n] = reach.theta[n];
  return 0.5 * (mid + reach.theta);
}

Reachability reachability(const Chain& chain, double theta_begin, double theta_end) {
  Reachability out;
  const Eigen::Index n = chain.ds.size();
  out.k_lo.resize(n + 1);
  out.k_hi.resize(n + 1);
  auto fail_at = [&](Eigen::Index k, const std::string& reason) {
    out.outcome = Reachability::Outcome::Infeasible;
    out.failed_index = k;
    out.reason = reason;
  };
  if (theta_end < chain.x_lo[n] * (1 - 1e-12) || theta_end > chain.x_hi[n] * (1 + 1e-12)) {
    fail_at(n, "the end speed is outside the feasible speeds at s_N");
    push_unique(out.binding, theta_end > chain.x_hi[n] ? chain.x_hi_id[static_cast<size_t>(n)]
                                                       : chain.x_lo_id[static_cast<size_t>(n)]);
    return out;
  }
  out.k_lo[n] = out.k_hi[n] = theta_end;

  // Backward pass: K_k = {θ_k : ∃ θ_{k+1} ∈ K_{k+1} with (θ_k, θ_{k+1}) on interval k's polygon}.
  Polygon2d poly;
  // Polygons are stored as they come (interval N-1 first).
  reserve_polygons(out, n, kPolygonVertices);
  out.start.resize(static_cast<size_t>(n));
  out.size.resize(static_cast<size_t>(n));
  for (Eigen::Index k = n - 1; k >= 0; --k) {
    interval_polygon(poly, chain.x_lo[k], chain.x_hi[k], out.k_lo[k + 1], out.k_hi[k + 1], chain.rows(k));
    if (poly.empty()) {
      fail_at(k, "no speed at this grid point can reach the end of the path");
      push_unique(out.binding, poly.emptied_by().id);
      push_unique(out.binding, poly.certificate_edge(0).id);
      push_unique(out.binding, poly.certificate_edge(1).id);
      return out;
    }
    store_polygon(out, k, poly);
    // θ_0 is the given start speed, so an unbounded K_0 (e.g. p'(s_0) = 0 with velocity limits only)
    // bounds nothing that is free; elsewhere it means the speed has no limit there.
    if (k > 0 && out.k_hi[k] >= chain.cap * (1 - 1e-9)) {
      out.outcome = Reachability::Outcome::Unbounded;
      out.failed_index = k;
      out.reason = "nothing bounds the speed here";
      return out;
    }
  }

  const double tol0 = 1e-12 * std::max(1.0, out.k_hi[0]);
  if (theta_begin < out.k_lo[0] - tol0 || theta_begin > out.k_hi[0] + tol0) {
    // The start speed is not controllable. Locate the failure: the first grid point whose forward-
    // reachable interval R_k misses K_k, with the rows that limit R_k there.
    double r_lo = theta_begin, r_hi = theta_begin;
    for (Eigen::Index k = 0; k < n; ++k) {
      poly.reset(r_lo, r_hi, chain.x_lo[k + 1], chain.x_hi[k + 1]);
      clip_rows(poly, chain.rows(k));
      if (poly.empty()) {
        fail_at(k + 1, "no admissible speed here from the start speed");
        push_unique(out.binding, poly.emptied_by().id);
        push_unique(out.binding, poly.certificate_edge(0).id);
        push_unique(out.binding, poly.certificate_edge(1).id);
        return out;
      }
      // Range of θ_{k+1}: extremes of y over the polygon.
      const auto& vs = poly.vertices();
      size_t imax = 0, imin = 0;
      for (size_t j = 1; j < vs.size(); ++j) {
        if (vs[j].y > vs[imax].y) imax = j;
        if (vs[j].y < vs[imin].y) imin = j;
      }
      r_lo = vs[imin].y;
      r_hi = vs[imax].y;
      const double tol = 1e-12 * std::max(1.0, out.k_hi[k + 1]);
      const bool too_slow = r_hi < out.k_lo[k + 1] - tol;
      const bool too_fast = r_lo > out.k_hi[k + 1] + tol;
      if (too_slow || too_fast) {
        fail_at(k + 1, too_slow ? "the speed needed here to reach the end cannot be reached from the start"
                                : "the path cannot slow down enough here to reach the end");
        const size_t v = too_slow ? imax : imin;
        const auto& es = poly.edges();
        push_unique(out.binding, es[v].id);
        push_unique(out.binding, es[(v + 1) % es.size()].id);
        return out;
      }
    }
    fail_at(0, "the start speed is outside the controllable set");
    return out;
  }
  out.theta = forward_pass(out, std::clamp(theta_begin, out.k_lo[0], out.k_hi[0]), nullptr);
  out.theta[0] = theta_begin;
  out.theta_is_greedy = true;
  return out;
}

bool reachability_pair(const Chain& chain, double theta_begin, double theta_end, Reachability& relaxed,
                       Reachability& full) {
  const Eigen::Index n = chain.ds.size();
  if (theta_end < chain.x_lo[n] * (1 - 1e-12) || theta_end > chain.x_hi[n] * (1 + 1e-12)) return false;
  Reachability* outs[2] = {&relaxed, &full};
  for (Reachability* o : outs) {
    o->outcome = Reachability::Outcome::Feasible;
    o->k_lo.resize(n + 1);
    o->k_hi.resize(n + 1);
    o->k_lo[n] = o->k_hi[n] = theta_end;
  }
  Polygon2d pr, pf;
  // The full analysis stores only the polygons that a coupling row or its own K_{k+1} cut (1.5 per interval
  // on average on the arm corpus, at most 2.8).
  reserve_polygons(relaxed, n, kPolygonVertices);
  reserve_polygons(full, n, 3);
  for (Reachability* o : outs) {
    o->start.resize(static_cast<size_t>(n));
    o->size.resize(static_cast<size_t>(n));
  }
  relaxed.base = nullptr;
  full.base = &relaxed;
  full.in_base.assign(static_cast<size_t>(n), 0);
  for (Eigen::Index k = n - 1; k >= 0; --k) {
    interval_polygon(pr, chain.x_lo[k], chain.x_hi[k], relaxed.k_lo[k + 1], relaxed.k_hi[k + 1], chain.relaxed_rows(k));
    if (pr.empty()) return false;
    // K_full ⊆ K_relaxed, so the full polygon is the relaxed one cut to θ_{k+1} ∈ K_full,k+1 and by
    // the coupling rows: one clipping pass serves both analyses. Most intervals have no coupling row and
    // meet the same K_{k+1}: nothing can cut, and the copy is skipped.
    const View<Line> coupled = chain.coupled_rows(k);
    const bool cut_hi = full.k_hi[k + 1] < relaxed.k_hi[k + 1], cut_lo = full.k_lo[k + 1] > relaxed.k_lo[k + 1];
    bool cut = false;
    if (cut_hi || cut_lo || !coupled.empty()) {
      pf.assign(pr);
      if (cut_hi) cut |= pf.clip({0.0, 1.0, full.k_hi[k + 1], kBoxYHigh});
      if (cut_lo && !pf.empty()) cut |= pf.clip({0.0, -1.0, -full.k_lo[k + 1], kBoxYLow});
      for (const Line& r : coupled)
        if (!pf.empty()) cut |= pf.clip(r);
      if (pf.empty()) return false;
    }
    // Usually nothing cut: the full analysis reads the relaxed one's copy of the polygon.
    full.in_base[static_cast<size_t>(k)] = !cut;
    const Polygon2d* polys[2] = {&pr, &pf};
    for (int i = 0; i < 2; ++i) {
      const Polygon2d& p = *polys[i];
      Reachability& o = *outs[i];
      if (i == 1 && !cut) {
        o.k_lo[k] = relaxed.k_lo[k];
        o.k_hi[k] = relaxed.k_hi[k];
        continue;
      }
      store_polygon(o, k, p);
      if (k > 0 && outs[i]->k_hi[k] >= chain.cap * (1 - 1e-9)) return false;  // K_0: θ_0 is given
    }
  }
  for (int i = 0; i < 2; ++i) {
    Reachability& o = *outs[i];
    const double tol0 = 1e-12 * std::max(1.0, o.k_hi[0]);
    if (theta_begin < o.k_lo[0] - tol0 || theta_begin > o.k_hi[0] + tol0) return false;
  }
  relaxed.theta = forward_pass(relaxed, std::clamp(theta_begin, relaxed.k_lo[0], relaxed.k_hi[0]), nullptr);
  relaxed.theta[0] = theta_begin;
  relaxed.theta_is_greedy = true;
  // The full greedy profile, reusing the relaxed one where the interval's polygon is the relaxed one
  // (in_base): only the stretches after a cut are sliced again.
  full.theta = guided_pass(full, std::clamp(theta_begin, full.k_lo[0], full.k_hi[0]), nullptr, &relaxed.theta,
                           &full.in_base);
  full.theta[0] = theta_begin;
  full.theta_is_greedy = true;
  return true;
}

bool avoid_stopped_profile(const Chain& chain, Reachability& reach, double th0, Eigen::VectorXd& theta) {
  if (!has_stopped_interval(theta)) return true;
  if (chain.lattice) return false;
  Eigen::VectorXd start = unstopped_profile(reach, th0);
  if (has_stopped_interval(start)) return false;
  theta = reach.theta = std::move(start);
  reach.theta_is_greedy = false;
  return true;
}

}  // namespace pathpace::detail
