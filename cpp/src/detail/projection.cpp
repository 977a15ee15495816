#include "detail/projection.hpp"

#include "detail/glpk_guard.hpp"
#include "detail/glpk_util.hpp"

#include <cmath>
#include <limits>

#include <glpk.h>

namespace pathpace::detail {

Projection project_polytope(const PolytopeLp& in, double relative_tolerance, int max_lps) {
  PolytopeProjector p;
  return p.project(in, relative_tolerance, max_lps);
}

PolytopeProjector::~PolytopeProjector() { release(); }

void PolytopeProjector::release() {
  if (lp_) glp_delete_prob(lp_);
  lp_ = nullptr;
  rows_ = cols_ = -1;
}

Projection PolytopeProjector::project(const PolytopeLp& in, double relative_tolerance, int max_lps) {
  Projection out;
  const int rows = static_cast<int>(in.A.rows()), cols = static_cast<int>(in.A.cols());
  glp_term_out(GLP_OFF);
  GlpkHookState state;
  glp_error_hook(pathpace_glpk_error_hook, &state);
  if (setjmp(state.env)) {  // GLPK misuse: the environment is gone, and with it our problem
    glp_error_hook(nullptr, nullptr);
    glp_free_env();
    lp_ = nullptr;
    rows_ = cols_ = -1;
    out.outcome = Projection::Outcome::Failed;
    return out;
  }
  const bool warm = lp_ && rows == rows_ && cols == cols_;
  if (!warm) {
    release();
    lp_ = glp_create_prob();
    glp_set_obj_dir(lp_, GLP_MAX);
    glp_add_rows(lp_, rows);
    glp_add_cols(lp_, cols);
    rows_ = rows;
    cols_ = cols;
  }
  glp_prob* lp = lp_;
  for (int i = 0; i < rows; ++i) glpk_set_bounds(lp, true, i + 1, in.row_lo[i], in.row_hi[i]);
  for (int j = 0; j < cols; ++j) glpk_set_bounds(lp, false, j + 1, in.col_lo[j], in.col_hi[j]);
  glpk_load_dense(lp, in.A, ia_, ja_, ar_);
  // No scaling: GLPK's automatic scaling was seen to make the primal simplex declare small, plainly
  // feasible projection LPs infeasible (rows of torque balance next to stand-in bounds of 1e6).
  // A new problem starts from an advanced basis; a reloaded one keeps the previous point's statuses.
  if (!warm) glp_adv_basis(lp, 0);
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.presolve = GLP_OFF;
  parm.it_lim = 100 * (rows + cols) + 1000;  // never a hang: a cycling simplex ends as a failure

  // eq. (19): max v·(x, u) over the polytope; false if infeasible (or the solver fails).
  auto extremize = [&](double vx, double vu, Vertex& p) -> int {
    glp_set_obj_coef(lp, 1, vx);
    glp_set_obj_coef(lp, 2, vu);
    ++out.lp_solves;
    // Warm start from the previous direction's basis (these LPs are small: joints x (2 + contacts x
    // cone edges), so the exact fallback is affordable).
    const int st = glpk_solve_robust(lp, parm);
    if (st != GLP_OPT) return st == GLP_NOFEAS ? 0 : -1;
    p = {glp_get_col_prim(lp, 1), glp_get_col_prim(lp, 2)};
    return 1;
  };

  // Initial directions: the vertices of an equilateral triangle (sec. IV.C).
  std::vector<Vertex> poly;
  std::vector<double> normal_angle;  // direction that produced each vertex
  for (int i = 0; i < 3; ++i) {
    const double ang = 2.0 * M_PI * i / 3.0;
    Vertex p;
    const int r = extremize(std::cos(ang), std::sin(ang), p);
    if (r <= 0) {
      glp_error_hook(nullptr, nullptr);
      out.outcome = r == 0 ? Projection::Outcome::Empty : Projection::Outcome::Failed;
      return out;
    }
    poly.push_back(p);
  }
  // Expansion: edge (p_i, p_{i+1}) counter-clockwise; its outward normal is (dy, -dx).
  std::vector<char> final_edge(3, 0);
  double size = 0.0;
  for (const Vertex& p : poly) size = std::max(size, std::abs(p.x) + std::abs(p.y));
  size = std::max(size, 1e-12);
  size_t i = 0;
  while (out.lp_solves < max_lps) {
    // Find an edge still to expand.
    size_t e = poly.size();
    for (size_t t = 0; t < poly.size(); ++t)
      if (!final_edge[(i + t) % poly.size()]) {
        e = (i + t) % poly.size();
        break;
      }
    if (e == poly.size()) break;
    const Vertex& a = poly[e];
    const Vertex& b = poly[(e + 1) % poly.size()];
    double nx = b.y - a.y, nu = -(b.x - a.x);
    const double len = std::hypot(nx, nu);
    if (len <= 1e-14 * size) {  // coincident vertices: nothing to expand
      final_edge[e] = 1;
      continue;
    }
    nx /= len;
    nu /= len;
    Vertex q;
    if (extremize(nx, nu, q) != 1) {
      glp_error_hook(nullptr, nullptr);
      out.outcome = Projection::Outcome::Failed;
      return out;
    }
    // The gain is measured against the support value itself, not the polygon's size: vertices on the
    // stand-in bounds (1e6) would otherwise make every real edge look final.
    const double gain = nx * (q.x - a.x) + nu * (q.y - a.y);
    if (gain <= relative_tolerance * std::max(1.0, std::abs(nx * a.x + nu * a.y))) {
      final_edge[e] = 1;
    } else {
      poly.insert(poly.begin() + static_cast<long>(e) + 1, q);
      final_edge.insert(final_edge.begin() + static_cast<long>(e) + 1, 0);
      final_edge[e] = 0;
      size = std::max(size, std::abs(q.x) + std::abs(q.y));
    }
    i = e;
  }
  glp_error_hook(nullptr, nullptr);
  // Half-planes from the edges (dropping zero-length ones).
  for (size_t e = 0; e < poly.size(); ++e) {
    const Vertex& a = poly[e];
    const Vertex& b = poly[(e + 1) % poly.size()];
    double nx = b.y - a.y, nu = -(b.x - a.x);
    const double len = std::hypot(nx, nu);
    if (len <= 1e-14 * size) continue;
    nx /= len;
    nu /= len;
    out.halfplanes.push_back({nx, nu, nx * a.x + nu * a.y, static_cast<int>(out.halfplanes.size())});
    out.vertices.push_back(a);
  }
  out.outcome = Projection::Outcome::Polygon;
  return out;
}

}  // namespace pathpace::detail
