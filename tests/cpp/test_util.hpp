#pragma once
// Helpers shared by the C++ tests (header-only).
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "pathpace/errors.hpp"
#include "pathpace/path.hpp"

namespace pathpace::test {

// The message of the InvalidInput that f throws, or "(no InvalidInput)": compared with the exact message
// the validation must give (house rule 2). Other exceptions propagate and fail the test.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no InvalidInput)";
}

// T of eq. (27) for squared speeds θ at the grid points of intervals of lengths ds:
// Σ 2 Δs_k / (√θ_k + √θ_{k+1}).
inline double duration_of(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta) {
  double T = 0.0;
  for (Eigen::Index k = 0; k < ds.size(); ++k) T += 2 * ds[k] / (std::sqrt(theta[k]) + std::sqrt(theta[k + 1]));
  return T;
}

// A path on s in [0, 1] in closed form: f(s, q, dq, ddq) writes p(s), p'(s), p''(s). s outside [0, 1] is
// clamped, as the Path contract asks.
class ClosedFormPath : public Path {
 public:
  using Formula = std::function<void(double, Eigen::Ref<Eigen::VectorXd>, Eigen::Ref<Eigen::VectorXd>,
                                     Eigen::Ref<Eigen::VectorXd>)>;
  ClosedFormPath(int dof, Formula f) : dof_(dof), f_(std::move(f)) {}
  int dof() const override { return dof_; }
  double s_begin() const override { return 0.0; }
  double s_end() const override { return 1.0; }
  using Path::evaluate;
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override {
    f_(std::clamp(s, 0.0, 1.0), q, dq, ddq);
  }

 private:
  int dof_;
  Formula f_;
};

}  // namespace pathpace::test
