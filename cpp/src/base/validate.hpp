#pragma once
// Input validation shared by every public entry point. Messages follow the house format:
// "<argument>[<index>] = <value> must be <expectation>".

#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Core>

#include "pathpace/errors.hpp"

namespace pathpace::detail {

inline std::string fmt(double v) {
  std::ostringstream os;
  os.precision(12);
  os << v;
  return os.str();
}

[[noreturn]] inline void fail(const std::string& msg) { throw InvalidInput(msg); }

/// "name[i]" or "name[i, j]"
inline std::string at(const std::string& name, Eigen::Index i) { return name + "[" + std::to_string(i) + "]"; }
inline std::string at(const std::string& name, Eigen::Index i, Eigen::Index j) {
  return name + "[" + std::to_string(i) + ", " + std::to_string(j) + "]";
}

/// Every entry finite (no NaN, no +-inf).
template <typename Derived>
void require_finite(const std::string& name, const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j))) {
        const std::string where = (m.cols() == 1) ? at(name, i) : (m.rows() == 1 ? at(name, j) : at(name, i, j));
        fail(where + " = " + fmt(m(i, j)) + " must be finite");
      }
}

/// No NaN (infinities allowed, e.g. an absent limit).
template <typename Derived>
void require_not_nan(const std::string& name, const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (std::isnan(m(i, j))) {
        const std::string where = (m.cols() == 1) ? at(name, i) : (m.rows() == 1 ? at(name, j) : at(name, i, j));
        fail(where + " = nan must be a number");
      }
}

inline void require_size(const std::string& name, Eigen::Index got, Eigen::Index expected,
                         const std::string& what = "") {
  if (got != expected)
    fail(name + " has size " + std::to_string(got) + ", expected " + std::to_string(expected) +
         (what.empty() ? "" : " (" + what + ")"));
}

inline void require_shape(const std::string& name, Eigen::Index rows, Eigen::Index cols, Eigen::Index erows,
                          Eigen::Index ecols, const std::string& what = "") {
  if (rows != erows || cols != ecols)
    fail(name + " has shape (" + std::to_string(rows) + ", " + std::to_string(cols) + "), expected (" +
         std::to_string(erows) + ", " + std::to_string(ecols) + ")" + (what.empty() ? "" : " (" + what + ")"));
}

/// Strictly increasing sequence.
template <typename Derived>
void require_increasing(const std::string& name, const Eigen::DenseBase<Derived>& v) {
  for (Eigen::Index i = 1; i < v.size(); ++i)
    if (!(v[i] > v[i - 1]))
      fail(at(name, i) + " = " + fmt(v[i]) + " must be > " + at(name, i - 1) + " = " + fmt(v[i - 1]) +
           " (strictly increasing)");
}

}  // namespace pathpace::detail
