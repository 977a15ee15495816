#include "lp/slice_lp.hpp"

#include "lp/binding_rule.hpp"

namespace pathpace::detail {

void SliceLp::load(const PolytopeLp& lp) {
  lp_ = &lp;
  dense_.load(lp, false);
  norms_ = false;
  top_here_ = false;
}

int SliceLp::extreme(double sign, double& x, PolytopeProjector::FixedColumn* fixed,
                     const std::vector<signed char>* start) {
  const PolytopeLp& lp = *lp_;
  const int end = sign > 0 ? 0 : 1, rows = static_cast<int>(lp.A.rows());
  std::vector<signed char>& basis = basis_[end];
  if (fixed && fixed->label && !norms_) row_norm_ = lp.A.rowwise().norm(), norms_ = true;
  const size_t total = static_cast<size_t>(rows + lp.A.cols());
  const std::vector<signed char>& from = start && start->size() == total ? *start : basis;
  auto solved_from = [&](const std::vector<signed char>& b) {
    return b.size() == total && dense_.set_basis(b.data(), false) && dense_.maximize(sign, 0.0) == DenseSimplex::kOptimal;
  };
  bool solved = solved_from(from);
  if (!solved && end == 1 && top_here_) solved = solved_from(basis_[0]);
  if (!solved && end == 0 && &from != &basis) solved = solved_from(basis);
  if (solved) {
    ++dense;
    if (end == 0) top_here_ = true;
    const std::vector<signed char>& stat = dense_.state().stat;
    basis = stat;
    x = dense_.x();
    if (fixed) {
      const int k = rows + fixed->column;
      fixed->slope = dense_.reduced_cost(k);
      dense_.bound_range(k, fixed->from, fixed->to);
      fixed->binding = fixed->label ? binding_rule(lp, row_norm_.data(), 2, [&](int v) { return stat[static_cast<size_t>(v)]; },
                                                   [&](int v) { return dense_.reduced_cost(v); })
                                    : kBindingUnknown;
    }
    return 1;
  }
  ++glpk;
  objective_.setZero(lp.A.cols());
  objective_[0] = sign;
  const int st = glpk_[end].maximize(lp, objective_, z_, fixed, &basis);
  if (st != 1) basis.clear();
  else x = z_[0];
  if (end == 0) top_here_ = st == 1;
  return st == 1 ? 1 : st == 0 ? 0 : -1;
}

}  // namespace pathpace::detail
