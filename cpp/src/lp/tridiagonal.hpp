#pragma once
// A general tridiagonal solve (the bases of the chain LP, see ChainSimplex in chain_simplex.hpp).

#include <vector>

namespace pathpace::detail {

/// Solves l_j x_{j-1} + d_j x_j + u_j x_{j+1} = r_j (j = 0..n-1; l_0 and u_{n-1} are ignored) by Gaussian
/// elimination with partial pivoting (LAPACK's gtsv scheme: a row swap fills a second superdiagonal, kept in
/// u2). The bases of the chain LP are not diagonally dominant, so Thomas' recurrence without pivoting could
/// divide by a small pivot. Returns false if a pivot is zero (a singular matrix) or the solution is not
/// finite. Overwrites d (with the reciprocals of the pivots), u and u2 (l is only read); on success r holds x.
bool solve_tridiagonal(const std::vector<double>& l, std::vector<double>& d, std::vector<double>& u,
                       std::vector<double>& r, std::vector<double>& u2);

}  // namespace pathpace::detail
