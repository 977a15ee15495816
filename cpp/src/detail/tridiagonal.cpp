#include "detail/tridiagonal.hpp"

#include <cmath>
#include <cstddef>
#include <utility>

namespace pathpace::detail {

bool solve_tridiagonal(std::vector<double>& l, std::vector<double>& d, std::vector<double>& u, std::vector<double>& r,
                       std::vector<double>& u2) {
  const std::size_t n = d.size();
  u2.assign(n, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    // Eliminate l_{j+1} (the entry below d_j).
    if (std::abs(d[j]) >= std::abs(l[j + 1])) {
      if (d[j] == 0.0) return false;
      const double f = l[j + 1] / d[j];
      d[j + 1] -= f * u[j];
      r[j + 1] -= f * r[j];
    } else {
      // Swap rows j and j+1: row j+1 is (l_{j+1}, d_{j+1}, u_{j+1}) in columns j, j+1, j+2.
      const double f = d[j] / l[j + 1];
      d[j] = l[j + 1];
      const double dj1 = d[j + 1];
      d[j + 1] = u[j] - f * dj1;
      u[j] = dj1;
      if (j + 2 < n) {
        u2[j] = u[j + 1];
        u[j + 1] = -f * u2[j];
      }
      std::swap(r[j], r[j + 1]);
      r[j + 1] -= f * r[j];
    }
  }
  if (n == 0) return true;
  if (d[n - 1] == 0.0) return false;
  r[n - 1] /= d[n - 1];
  if (n > 1) r[n - 2] = (r[n - 2] - u[n - 2] * r[n - 1]) / d[n - 2];
  for (std::size_t j = n >= 2 ? n - 2 : 0; j-- > 0;) r[j] = (r[j] - u[j] * r[j + 1] - u2[j] * r[j + 2]) / d[j];
  for (double v : r)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace pathpace::detail
