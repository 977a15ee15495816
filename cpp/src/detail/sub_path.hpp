#pragma once
// The tail [s0, s_end] of a path, for TimeScalingProblem::restarted: the same p(s) on a shorter domain.

#include <algorithm>
#include <memory>

#include "pathpace/path.hpp"

namespace pathpace::detail {

class SubPath final : public Path {
 public:
  SubPath(std::shared_ptr<const Path> parent, double s0) : parent_(std::move(parent)), s0_(s0) {}
  int dof() const override { return parent_->dof(); }
  double s_begin() const override { return s0_; }
  double s_end() const override { return parent_->s_end(); }
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override {
    parent_->evaluate(std::max(s, s0_), q, dq, ddq);  // clamped like every path (the parent clamps the end)
  }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                Eigen::MatrixXd& ddq) const override {
    parent_->evaluate(s.cwiseMax(s0_), q, dq, ddq);  // the parent's batch evaluation, if it has a fast one
  }

 private:
  std::shared_ptr<const Path> parent_;
  double s0_;
};

}  // namespace pathpace::detail
