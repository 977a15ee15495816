#include "pathpace/function_path.hpp"

#include <cmath>
#include <string>

#include "base/validate.hpp"

namespace pathpace {

namespace {

// One of q, dq, ddq as the function left it: (m, n), every entry finite.
void check(const Eigen::MatrixXd& v, const char* what, const Eigen::VectorXd& s, int n) {
  if (v.rows() != s.size() || v.cols() != n)
    detail::fail(std::string("FunctionPath: the function's ") + what + " has shape (" + std::to_string(v.rows()) +
                       ", " + std::to_string(v.cols()) + ") for " + std::to_string(s.size()) + " values of s, expected (" +
                       std::to_string(s.size()) + ", " + std::to_string(n) + ")");
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      if (!std::isfinite(v(i, j)))
        detail::fail(std::string("FunctionPath: the function's ") + what + "(" + std::to_string(i) + ", " +
                           std::to_string(j) + ") = " + detail::fmt(v(i, j)) + " at s = " + detail::fmt(s[i]) + " must be finite");
}

}  // namespace

FunctionPath::FunctionPath(Function function, int dof, double s_begin, double s_end)
    : function_(std::move(function)), dof_(dof), s_begin_(s_begin), s_end_(s_end) {
  if (!function_) detail::fail("FunctionPath: function is empty, expected p, p', p'' on a vector of s");
  if (dof < 1) detail::fail("FunctionPath: dof = " + std::to_string(dof) + " must be >= 1");
  if (!(std::isfinite(s_begin) && std::isfinite(s_end) && s_begin < s_end))
    detail::fail("FunctionPath: (s_begin, s_end) = (" + detail::fmt(s_begin) + ", " + detail::fmt(s_end) +
                       ") must be finite with s_begin < s_end");
}

void FunctionPath::evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                            Eigen::Ref<Eigen::VectorXd> ddq) const {
  Eigen::MatrixXd mq, mdq, mddq;
  evaluate(Eigen::VectorXd::Constant(1, s), mq, mdq, mddq);
  q = mq.row(0).transpose();
  dq = mdq.row(0).transpose();
  ddq = mddq.row(0).transpose();
}

void FunctionPath::evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                            Eigen::MatrixXd& ddq) const {
  const Eigen::VectorXd x = s.cwiseMax(s_begin_).cwiseMin(s_end_);
  function_(x, q, dq, ddq);
  check(q, "q", x, dof_);
  check(dq, "dq", x, dof_);
  check(ddq, "ddq", x, dof_);
}

}  // namespace pathpace
