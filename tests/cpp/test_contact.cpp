// Contacts in C++: a free object carried by a robot through robot–robot contacts (closed-form optimum),
// model combination and the force-distribution LP.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "pathpace/pathpace.hpp"
#include "test_fixtures.hpp"

using namespace pathpace;
using test::corners;
using test::lifter_with_box;

TEST(Contact, BoxCarriedByFrictionHasTheBangBangOptimum) {
  auto model = lifter_with_box();
  ASSERT_EQ(model->nq(), 7);
  const int N = 40;
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(N + 1, 0.0, 1.0);
  ps.q = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.dq = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.ddq = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.q.col(0) = ps.q.col(1) = ps.s;  // the slide and the box's x
  ps.dq.col(0).setOnes();
  ps.dq.col(1).setOnes();
  auto path = std::make_shared<SampledPath>(ps.s, ps.q, ps.dq, ps.ddq);
  TimeScalingProblem prob(path, ps.s);
  ContactOptions opt;
  opt.cone_edges = 4;
  auto contact = std::make_shared<ContactConstraint>(model, corners(0.5), opt);
  EXPECT_LT(contact->max_drift(ps), 1e-14);
  prob.add_constraint(contact);
  const Result res = prob.solve();
  ASSERT_EQ(res.status, Status::Optimal);
  const double a = 0.5 * 9.81;
  EXPECT_NEAR(res.duration, 2.0 * std::sqrt(1.0 / a), 1e-9);
  // Mid-acceleration: the four corners push the box with m a forward and m g up, margin >= 0.
  const Trajectory traj = res.trajectory();
  ASSERT_TRUE(traj.contacts());
  Eigen::VectorXd t(1);
  t << 0.25 * res.duration;
  Eigen::VectorXi phase;
  const ContactForces f = traj.contact_forces(t, &phase)[0];
  EXPECT_EQ(phase, Eigen::VectorXi::Constant(1, -1));  // no phases
  ASSERT_TRUE(f.feasible);
  EXPECT_GE(f.margin, -1e-8);
  const Eigen::Vector3d total = f.forces.colwise().sum().transpose();
  EXPECT_NEAR(total.x(), 2.0 * a, 1e-7);
  EXPECT_NEAR(total.z(), 2.0 * 9.81, 1e-7);
  EXPECT_NEAR(f.torques[0], 5.0 * a, 1e-7);  // platform and box
}

TEST(Contact, WrenchesAndCentreOfPressureOfTheCarriedBox) {
  // The box on the platform's four corners, accelerating at a = μ g: the box link takes m (a, 0, g) and
  // the platform the opposite; the box's centre of pressure is the corners' normal-force-weighted mean.
  auto model = lifter_with_box();
  const int N = 20;
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(N + 1, 0.0, 1.0);
  ps.q = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.dq = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.ddq = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.q.col(0) = ps.q.col(1) = ps.s;
  ps.dq.col(0).setOnes();
  ps.dq.col(1).setOnes();
  TimeScalingProblem prob(std::make_shared<SampledPath>(ps.s, ps.q, ps.dq, ps.ddq), ps.s);
  ContactOptions opt;
  opt.cone_edges = 4;
  prob.add_constraint(std::make_shared<ContactConstraint>(model, corners(0.5), opt));
  const Result res = prob.solve();
  ASSERT_EQ(res.status, Status::Optimal);
  const Trajectory traj = res.trajectory();
  Eigen::VectorXd t(2);
  t << 0.25 * res.duration, 0.75 * res.duration;
  const ContactWrenches w = traj.contact_wrenches(t);
  ASSERT_EQ(w.links, (std::vector<std::string>{"box", "platform"}));
  const std::vector<ContactForces> f = traj.contact_forces(t);
  const double a = 0.5 * 9.81;
  for (Eigen::Index i = 0; i < 2; ++i) {
    const Eigen::Vector3d box = w.force.block<1, 3>(i, 0).transpose(), platform = w.force.block<1, 3>(i, 3).transpose();
    EXPECT_NEAR(box.x(), (i == 0 ? 2.0 : -2.0) * a, 1e-7);
    EXPECT_NEAR(box.z(), 2.0 * 9.81, 1e-7);
    EXPECT_LT((box + platform).norm(), 1e-12);
    EXPECT_NEAR(w.normal_force(i, 0), box.z(), 1e-12);    // the normal is +z into the box
    EXPECT_NEAR(w.normal_force(i, 1), box.z(), 1e-12);    // and -z into the platform, which is pushed down
    Eigen::Vector3d cop = Eigen::Vector3d::Zero();
    const double x_box = traj.q(t.segment(i, 1))(0, 1);
    for (int j = 0; j < 4; ++j) cop += f[static_cast<size_t>(i)].forces(j, 2) * (Eigen::Vector3d(x_box, 0, 0) + corners(0.5)[static_cast<size_t>(j)].point);
    cop /= box.z();
    EXPECT_LT((w.center_of_pressure.block<1, 3>(i, 0).transpose() - cop).norm(), 1e-12);
    EXPECT_LT((w.center_of_pressure.block<1, 3>(i, 3).transpose() - cop).norm(), 1e-12);  // the same plane
  }
}

TEST(Contact, ForceDistributionReportsMissingForces) {
  // The box at rest on the platform, asked to accelerate at 2 g sideways: friction cannot, and the
  // margin says by how much (negative); with no contact at all the LP has no solution.
  auto model = lifter_with_box();
  ContactOptions opt;
  opt.cone_edges = 4;
  ContactConstraint c(model, corners(0.5), opt);
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(2, 7), qd = q, qdd = q;
  qdd(0, 0) = qdd(0, 1) = 0.2 * 9.81;
  qdd(1, 0) = qdd(1, 1) = 2.0 * 9.81;
  const auto f = c.force_distribution(q, qd, qdd);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_TRUE(f[0].feasible && f[1].feasible);
  EXPECT_GT(f[0].margin, 0.0);
  EXPECT_LT(f[1].margin, -1.0);
  ContactConstraint none(model, {}, opt);
  const auto g = none.force_distribution(q, qd, qdd);
  EXPECT_FALSE(g[0].feasible);
  EXPECT_TRUE(std::isinf(g[0].margin));
  EXPECT_TRUE(std::isnan(g[0].torques.sum()));
  EXPECT_THROW(c.force_distribution(q.leftCols(3), qd, qdd), InvalidInput);
}

TEST(Contact, CombineRejectsDuplicateLinks) {
  const RobotModel box = RobotModel::free_object("box", 1.0);
  try {
    RobotModel::combine({box, box});
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("has a link 'box' that an earlier part also has"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RobotModel::combine({}), InvalidInput);
  EXPECT_THROW(RobotModel::free_object("b", -1.0), InvalidInput);
}
