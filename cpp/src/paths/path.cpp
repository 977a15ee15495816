#include "pathpace/path.hpp"

namespace pathpace {

void Path::evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                    Eigen::MatrixXd& ddq) const {
  const Eigen::Index m = s.size();
  const int n = dof();
  q.resize(m, n);
  dq.resize(m, n);
  ddq.resize(m, n);
  Eigen::VectorXd qi(n), dqi(n), ddqi(n);
  for (Eigen::Index i = 0; i < m; ++i) {
    evaluate(s[i], qi, dqi, ddqi);
    q.row(i) = qi.transpose();
    dq.row(i) = dqi.transpose();
    ddq.row(i) = ddqi.transpose();
  }
}

Eigen::MatrixXd Path::q(const Eigen::Ref<const Eigen::VectorXd>& s) const {
  Eigen::MatrixXd q, dq, ddq;
  evaluate(s, q, dq, ddq);
  return q;
}

Eigen::MatrixXd Path::dq(const Eigen::Ref<const Eigen::VectorXd>& s) const {
  Eigen::MatrixXd q, dq, ddq;
  evaluate(s, q, dq, ddq);
  return dq;
}

Eigen::MatrixXd Path::ddq(const Eigen::Ref<const Eigen::VectorXd>& s) const {
  Eigen::MatrixXd q, dq, ddq;
  evaluate(s, q, dq, ddq);
  return ddq;
}

}  // namespace pathpace
