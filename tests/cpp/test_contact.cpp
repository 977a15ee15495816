// Contacts in C++: a free object carried by a robot through robot–robot contacts (closed-form optimum),
// model combination and the force-distribution LP.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <memory>

#include "pathpace/pathpace.hpp"
#include "test_fixtures.hpp"

using namespace pathpace;
using test::box_options;
using test::corners;
using test::lifter_with_box;

namespace {

// The platform and the box on it slide together from x = 0 to 1: N intervals.
PathSamples slide_together(int N) {
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(N + 1, 0.0, 1.0);
  ps.q = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.dq = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.ddq = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.q.col(0) = ps.q.col(1) = ps.s;  // the slide and the box's x
  ps.dq.col(0).setOnes();
  ps.dq.col(1).setOnes();
  return ps;
}

}  // namespace

TEST(Contact, BoxCarriedByFrictionHasTheBangBangOptimum) {
  auto model = lifter_with_box();
  ASSERT_EQ(model->nq(), 7);
  const PathSamples ps = slide_together(40);
  auto path = std::make_shared<SampledPath>(ps.s, ps.q, ps.dq, ps.ddq);
  TimeScalingProblem prob(path, ps.s);
  ContactOptions opt = box_options();
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
  const PathSamples ps = slide_together(20);
  TimeScalingProblem prob(std::make_shared<SampledPath>(ps.s, ps.q, ps.dq, ps.ddq), ps.s);
  ContactOptions opt = box_options();
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

TEST(Contact, CentredDistributionOfABoxAtRestIsItsSymmetricSplit) {
  // The box at rest on four corners symmetric about its centre of mass: the physical force set is
  // invariant under both mirrors of the sole and under f_t -> -f_t at every corner (even k, symmetric
  // slide limits), so its unique analytic centre is a quarter of the weight at each corner, no tangential
  // force. The LP's vertex need not be (it is any optimum of its margin).
  auto model = lifter_with_box();
  ContactConstraint c(model, corners(0.5), box_options());
  const Eigen::MatrixXd q = Eigen::MatrixXd::Zero(1, 7), qd = q, qdd = q;
  const ContactForces f = c.force_distribution(q, qd, qdd)[0];
  ASSERT_TRUE(f.feasible);
  EXPECT_TRUE(f.centred);
  const double weight = f.forces.col(2).sum();
  EXPECT_NEAR(weight, 2.0 * 9.81, 1e-6);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(f.forces(i, 2), weight / 4.0, 1e-9 * weight) << i;
    EXPECT_NEAR(f.forces(i, 0), 0.0, 1e-9 * weight) << i;
    EXPECT_NEAR(f.forces(i, 1), 0.0, 1e-9 * weight) << i;
  }
  // The smallest slack is that of the pyramid's facets at the quarter weight: μ cos(π/4) f_n / |(μ cos(π/4), 1)|.
  const double a = 0.5 * std::cos(M_PI / 4.0);
  EXPECT_NEAR(f.slack, a * weight / 4.0 / std::sqrt(1.0 + a * a), 1e-9 * weight);
  const ContactForces v = c.force_distribution(q, qd, qdd, ForceDistribution::Vertex)[0];
  EXPECT_FALSE(v.centred);
  EXPECT_EQ(v.margin, f.margin);  // the LP's margin either way
  EXPECT_LE(v.slack, f.slack + 1e-9 * weight);
}

TEST(Contact, ForceDistributionReportsMissingForces) {
  // The box at rest on the platform, asked to accelerate at 2 g sideways: friction cannot, and the
  // margin says by how much (negative); with no contact at all the LP has no solution.
  auto model = lifter_with_box();
  ContactOptions opt = box_options();
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

namespace {
// The range of u = s̈ at x = ṡ² = 1 that rows a x + b u <= c allow at sample p.
std::pair<double, double> u_range(const ConstraintRows& r, Eigen::Index p) {
  double lo = -INFINITY, hi = INFINITY;
  for (Eigen::Index j = 0; j < r.rows(); ++j) {
    const double a = r.a(p, j), b = r.b(p, j), c = r.c(p, j);
    if (!std::isfinite(c) || b == 0.0) continue;
    if (b > 0) hi = std::min(hi, (c - a) / b);
    else lo = std::max(lo, (c - a) / b);
  }
  return {lo, hi};
}

// check_point's answer (the unreduced polytope: every point, its cone, its row) at (x, u) = (1, u).
int feasible_at(const ContactConstraint& c, const PathSamples& ps, Eigen::Index p, double u) {
  Eigen::Matrix<double, Eigen::Dynamic, 3> pin(4, 3);
  pin << 1, 0, 1, -1, 0, -1, 0, 1, u, 0, -1, -u;
  return c.check_point(ps, p, pin).feasible;
}
}  // namespace

TEST(Contact, PerPointMinimumReducesExactlyOnADenseBoxBottom) {
  // The box on 20 points (a 5 x 4 grid on its bottom, robot–robot contacts: the normals in the
  // platform's frame), each pushing at least 0.6 N: for an even k the LPs see the 4 corners' cones and
  // k/2 cross-section weights per point (docs/method.md), for an odd k every point with its row. The
  // accelerations allowed (friction, and tipping: the centre of mass 5 cm above the soles, which the
  // per-point minimum makes bind sooner) are those of the unreduced polytope: check_point's LP over
  // every point says feasible 1e-7 inside each end, infeasible (confirmed exactly) 1e-7 outside.
  auto model = lifter_with_box();
  std::vector<Contact> cons;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j) {
      Contact c = corners(2.5)[0];
      c.point = Eigen::Vector3d(-0.1 + 0.05 * i, -0.1 + 0.2 * j / 3.0, 0.0);
      cons.push_back(c);
    }
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(3, 0.0, 1.0);
  ps.q = Eigen::MatrixXd::Zero(3, 7);
  ps.dq = Eigen::MatrixXd::Zero(3, 7);
  ps.ddq = Eigen::MatrixXd::Zero(3, 7);
  ps.q.col(0) = ps.q.col(1) = ps.s;
  ps.dq.col(0).setOnes();
  ps.dq.col(1).setOnes();
  for (int k : {4, 8, 16, 5}) {
    ContactOptions opt;
    opt.cone_edges = k;
    opt.friction_margin = 0.2;
    ContactConstraint bare(model, cons, opt);
    opt.min_normal_force = 0.6;
    ContactConstraint c(model, cons, opt);
    EXPECT_EQ(c.projected_contacts().size(), k % 2 == 0 ? 4u : 20u) << k;
    EXPECT_EQ(c.section_contacts().size(), k % 2 == 0 ? 20u : 0u) << k;
    const ConstraintRows r = c.evaluate(ps), rb = bare.evaluate(ps);
    for (Eigen::Index p = 0; p < 3; ++p) {
      const auto [lo, hi] = u_range(r, p);
      ASSERT_TRUE(std::isfinite(lo) && std::isfinite(hi) && lo < 0.0 && hi > 0.0) << k;
      EXPECT_LT(hi, u_range(rb, p).second * (1 - 1e-3)) << k << ": the per-point minimum binds";
      const double tol = 1e-7 * (hi - lo);
      EXPECT_EQ(feasible_at(c, ps, p, hi - tol), 1) << k;
      EXPECT_EQ(feasible_at(c, ps, p, hi + tol), 0) << k;
      EXPECT_EQ(feasible_at(c, ps, p, lo + tol), 1) << k;
      EXPECT_EQ(feasible_at(c, ps, p, lo - tol), 0) << k;
    }
    // The LP's most robust forces (the vertex) at the largest acceleration keep every point's minimum, in its cone.
    Eigen::MatrixXd q = ps.q.topRows(1), qd = ps.dq.topRows(1), qdd = (1 - 1e-6) * u_range(r, 0).second * ps.dq.topRows(1);
    const ContactForces f = c.force_distribution(q, qd, qdd, ForceDistribution::Vertex)[0];
    ASSERT_TRUE(f.feasible);
    EXPECT_GE(f.margin, 0.0);
    const double mu = 2.5 * (1 - 0.2);
    for (int i = 0; i < 20; ++i) {
      EXPECT_GE(f.forces(i, 2), 0.6 - 1e-9) << k << " point " << i;
      EXPECT_LE(std::hypot(f.forces(i, 0), f.forces(i, 1)), mu * f.forces(i, 2) + 1e-9) << k << " point " << i;
    }
  }
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
