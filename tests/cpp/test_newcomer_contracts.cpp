// Contracts of issue 24 in C++: the contact-drift check (check_contact_drift, TimeScalingProblem::add_contacts),
// the time limit of a problem proven without SLP, the torque limits a Result carries, locked mimic joints.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "pathpace/pathpace.hpp"
#include "test_fixtures.hpp"

using namespace pathpace;
using test::box_options;
using test::corners;
using test::lifter_with_box;

namespace {

// The platform moves by s; the box by (1 + slip) s: its corners slide by slip m over s in [0, 1] on the platform.
std::shared_ptr<SampledPath> sliding_box_path(double slip, int N = 20) {
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(N + 1, 0.0, 1.0);
  ps.q = Eigen::MatrixXd::Zero(N + 1, 7);
  ps.dq = ps.ddq = ps.q;
  ps.q.col(0) = ps.s;
  ps.q.col(1) = (1.0 + slip) * ps.s;
  ps.dq.col(0).setOnes();
  ps.dq.col(1).setConstant(1.0 + slip);
  return std::make_shared<SampledPath>(ps.s, ps.q, ps.dq, ps.ddq);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ContactDrift, NamesTheContactWhereAndHowFar) {
  auto model = lifter_with_box();
  ContactOptions opt = box_options();
  const ContactConstraint c(model, corners(0.5), opt);
  TimeScalingProblem prob(sliding_box_path(0.05), 20);
  // Every corner slides by 5 cm (to rounding, which picks one of the four), farthest at the end (s = 1).
  const auto d = check_contact_drift(c, prob.samples(), 1e-2, DriftPolicy::Warn);
  ASSERT_TRUE(d.has_value());
  EXPECT_TRUE(d->contact >= 0 && d->contact < 4) << d->contact;
  EXPECT_EQ(d->link, "box");
  EXPECT_NEAR(d->drift, 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(d->s, 1.0);
  EXPECT_FALSE(check_contact_drift(c, prob.samples(), 0.06, DriftPolicy::Error).has_value());  // within
  // Auto: up to 10x the tolerance is let through; beyond, an error naming contact, s and drift.
  EXPECT_TRUE(check_contact_drift(c, prob.samples(), 0.006, DriftPolicy::Auto).has_value());
  const std::string msg = error_of([&] { check_contact_drift(c, prob.samples(), 0.004, DriftPolicy::Auto); });
  EXPECT_NE(msg.find("contact " + std::to_string(d->contact) + " (link 'box') moves by 0.05 m"), std::string::npos) << msg;
  EXPECT_NE(msg.find("s = 1"), std::string::npos) << msg;
  EXPECT_NE(error_of([&] { check_contact_drift(c, prob.samples(), 0.04, DriftPolicy::Error); }).find("moves by 0.05"),
            std::string::npos);
  EXPECT_NE(error_of([&] { check_contact_drift(c, prob.samples(), -1.0); }).find("drift_tolerance = -1"), std::string::npos);
}

TEST(ContactDrift, AddContactsRefusesOrRecordsAndTheResultSaysSo) {
  auto model = lifter_with_box();
  ContactOptions opt = box_options();
  auto c = std::make_shared<ContactConstraint>(model, corners(0.5), opt);
  TimeScalingProblem prob(sliding_box_path(0.05), 20);
  EXPECT_THROW(prob.add_contacts(c), InvalidInput);  // default: 1e-6 m, Auto
  EXPECT_TRUE(prob.constraints().empty());            // nothing added
  const std::vector<ContactDrift> warned = prob.add_contacts(c, 1e-6, DriftPolicy::Warn);
  ASSERT_EQ(prob.contact_drift().size(), 1u);
  ASSERT_EQ(warned.size(), 1u);  // what the caller warns about (Python: one UserWarning)
  EXPECT_EQ(warned[0].message(), prob.contact_drift()[0].message());
  const Result res = prob.solve();
  ASSERT_TRUE(res.ok()) << res.message;
  ASSERT_EQ(res.contact_drift.size(), 1u);
  EXPECT_NEAR(res.contact_drift[0].drift, 0.05, 1e-12);
  EXPECT_NE(res.message.find("the path moves its contacts"), std::string::npos) << res.message;
  // A path that keeps the box in place: nothing recorded, nothing said.
  TimeScalingProblem still(sliding_box_path(0.0), 20);
  EXPECT_TRUE(still.add_contacts(c).empty());
  EXPECT_TRUE(still.contact_drift().empty());
  const Result ok = still.solve();
  EXPECT_TRUE(ok.contact_drift.empty());
  EXPECT_EQ(ok.message.find("moves"), std::string::npos) << ok.message;
  // The contact constraint's torque limits are the ones the result carries (URDF effort, 1000 N on the slide).
  ASSERT_EQ(ok.tau_max.size(), 7);
  EXPECT_DOUBLE_EQ(ok.tau_max[0], 1000.0);
}

TEST(ContactDrift, PhasesAreCheckedOnTheirOwnStretch) {
  auto model = lifter_with_box();
  ContactOptions opt;
  opt.cone_edges = 4;
  TimeScalingProblem prob(sliding_box_path(0.05), 20);
  std::vector<ContactPhase> phases(2);
  phases[0] = {0.0, 0.5, corners(0.5), std::nullopt};
  phases[1] = {0.5, 1.0, corners(0.5), std::nullopt};
  const std::string msg = error_of([&] { prob.add_contact_phases(model, phases, opt); });
  EXPECT_NE(msg.find("phases[0]: contact 0 (link 'box') moves by 0.025 m"), std::string::npos) << msg;
  EXPECT_TRUE(prob.constraints().empty());
  const auto warned =
      prob.add_contact_phases(model, phases, opt, Eigen::VectorXd(), Eigen::VectorXd(), 1e-6, 1e-6, DriftPolicy::Warn);
  ASSERT_EQ(prob.contact_drift().size(), 2u);
  ASSERT_EQ(warned.size(), 2u);
  EXPECT_EQ(warned[1].constraint, "phases[1]");
  EXPECT_EQ(prob.contact_drift()[1].constraint, "phases[1]");
  EXPECT_NEAR(prob.contact_drift()[1].drift, 0.025, 1e-12);  // measured from where phase 1 begins
}

TEST(Solver, TimeLimitReachedBeforeTheSlpIsTheStatus) {
  // Velocity and acceleration limits on a spline: proven optimal by the reachability analysis (no SLP),
  // where the time limit used to go unchecked.
  Eigen::MatrixXd wp(3, 2);
  wp << 0.0, 0.0, 1.0, 0.5, 0.2, 1.5;
  TimeScalingProblem prob(std::make_shared<CubicSplinePath>(wp), 200);
  prob.add_velocity_limits(-Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones());
  prob.add_acceleration_limits(-2.0 * Eigen::Vector2d::Ones(), 2.0 * Eigen::Vector2d::Ones());
  const Result best = prob.solve();
  ASSERT_EQ(best.status, Status::Optimal) << best.message;
  ASSERT_EQ(best.stats.slp_iterations, 0);
  SolverOptions o;
  o.time_limit = 1e-9;
  const Result r = prob.solve(o);
  ASSERT_EQ(r.status, Status::TimeLimit) << r.message;
  EXPECT_TRUE(r.ok());
  EXPECT_NE(r.message.find("time_limit = 1e-09 s reached before the SLP"), std::string::npos) << r.message;
  EXPECT_EQ(r.duration, best.duration);  // the same proven timing, deterministically
  EXPECT_EQ(r.stats.gap, best.stats.gap);
}

TEST(RobotModel, ALockedMimicIsFrozenAloneOrMustAgreeWithItsJoint) {
  const std::string urdf = R"(<robot name="gripper">
 <link name="base"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="a"><inertial><mass value="0.1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="b"><inertial><mass value="0.1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <joint name="finger1" type="prismatic"><parent link="base"/><child link="a"/><axis xyz="0 1 0"/><limit lower="0" upper="0.04" velocity="0.2" effort="20"/></joint>
 <joint name="finger2" type="prismatic"><parent link="base"/><child link="b"/><axis xyz="0 -1 0"/><limit lower="0" upper="0.04" velocity="0.2" effort="20"/><mimic joint="finger1" multiplier="1" offset="0"/></joint>
</robot>)";
  RobotModelOptions o;
  EXPECT_TRUE(RobotModel::from_urdf_string(urdf, o).frozen_mimic_joints().empty());
  // Alone: frozen (finger1 still moves, the relation dropped for finger2), and said so.
  o.locked_joints = {{"finger2", 0.01}};
  const RobotModel alone = RobotModel::from_urdf_string(urdf, o);
  EXPECT_EQ(alone.nq(), 1);
  EXPECT_EQ(alone.frozen_mimic_joints(), std::vector<std::string>{"finger2"});
  EXPECT_TRUE(alone.mimic_joints().empty());
  // Combined models keep the record.
  EXPECT_EQ(RobotModel::combine({alone, RobotModel::free_object("box", 1.0)}).frozen_mimic_joints(),
            std::vector<std::string>{"finger2"});
  // With its joint, against the relation: refused, naming both.
  o.locked_joints = {{"finger1", 0.02}, {"finger2", 0.01}};
  std::string msg;
  try {
    RobotModel::from_urdf_string(urdf, o);
  } catch (const InvalidInput& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("'finger2' = 0.01 breaks its mimic relation (q = 1 * q_finger1 + 0): 'finger1' = 0.02 gives 0.02"),
            std::string::npos) << msg;
  o.locked_joints = {{"finger1", 0.02}, {"finger2", 0.02}};  // consistent: nothing frozen, nothing moves
  const RobotModel both = RobotModel::from_urdf_string(urdf, o);
  EXPECT_EQ(both.nq(), 0);
  EXPECT_TRUE(both.frozen_mimic_joints().empty());
  o.locked_joints = {{"finger1", 0.02}};  // the joint: its mimic follows
  EXPECT_TRUE(RobotModel::from_urdf_string(urdf, o).frozen_mimic_joints().empty());
}
