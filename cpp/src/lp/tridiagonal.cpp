#include "lp/tridiagonal.hpp"

#include <cmath>
#include <cstddef>
#include <utility>

namespace pathpace::detail {

bool solve_tridiagonal(const std::vector<double>& l, std::vector<double>& d, std::vector<double>& u,
                       std::vector<double>& r, std::vector<double>& u2) {
  const std::size_t n = d.size();
  u2.assign(n, 0.0);
  if (n == 0) return true;
  // Raw pointers: through the vectors' references every store would reload their data pointers. Each pivot's
  // reciprocal replaces it in d, so that the back substitution (a chain of dependent steps) multiplies where it
  // would divide: one division per row, and none on its critical path.
  const double* L = l.data();
  double *D = d.data(), *U = u.data(), *R = r.data(), *U2 = u2.data();
  for (std::size_t j = 0; j + 1 < n; ++j) {
    // Eliminate l_{j+1} (the entry below d_j).
    if (L[j + 1] == 0.0) {
      // Nothing to eliminate (about half the rows of a chain simplex basis: a constraint acts on its column and
      // one neighbour only). The general step would subtract 0 · l_{j+1} / d_j terms: the same values (up to
      // the sign of a zero), but with the division on the dependency chain into d_{j+1}.
      if (D[j] == 0.0) return false;
      D[j] = 1.0 / D[j];
    } else if (std::abs(D[j]) >= std::abs(L[j + 1])) {  // |d_j| >= |l_{j+1}| > 0 (NaN: the swap below)
      const double inv = 1.0 / D[j];
      const double f = L[j + 1] * inv;
      D[j] = inv;
      if (U[j] != 0.0) D[j + 1] -= f * U[j];  // (likewise: u_j is 0 on the other half of a chain basis's rows)
      R[j + 1] -= f * R[j];
    } else {
      // Swap rows j and j+1: row j+1 is (l_{j+1}, d_{j+1}, u_{j+1}) in columns j, j+1, j+2.
      const double inv = 1.0 / L[j + 1];
      const double f = D[j] * inv;
      D[j] = inv;
      const double dj1 = D[j + 1];
      D[j + 1] = U[j] - f * dj1;
      U[j] = dj1;
      if (j + 2 < n) {
        U2[j] = U[j + 1];
        U[j + 1] = -f * U2[j];
      }
      std::swap(R[j], R[j + 1]);
      R[j + 1] -= f * R[j];
    }
  }
  if (D[n - 1] == 0.0) return false;
  R[n - 1] /= D[n - 1];
  if (n > 1) R[n - 2] = (R[n - 2] - U[n - 2] * R[n - 1]) * D[n - 2];
  for (std::size_t j = n >= 2 ? n - 2 : 0; j-- > 0;) R[j] = (R[j] - U[j] * R[j + 1] - U2[j] * R[j + 2]) * D[j];
  for (std::size_t j = 0; j < n; ++j)
    if (!std::isfinite(R[j])) return false;
  return true;
}

}  // namespace pathpace::detail
