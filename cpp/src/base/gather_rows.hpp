#pragma once
// Rows of a matrix picked by index: the samples of one contact phase (ContactConstraint::evaluate projects a
// phase's own grid points, Trajectory::contact_forces gives each phase its own times).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace pathpace::detail {

/// Rows idx[0], idx[1], ... of m, in that order (a column vector gives its entries).
template <typename Matrix>
Matrix gather_rows(const Matrix& m, const std::vector<Eigen::Index>& idx) {
  Matrix out(static_cast<Eigen::Index>(idx.size()), m.cols());
  for (size_t i = 0; i < idx.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = m.row(idx[i]);
  return out;
}

}  // namespace pathpace::detail
