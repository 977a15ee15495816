// Contact phases (TimeScalingProblem::add_contact_phases): a hand that pushes a box and then brakes it
// (closed-form discrete optimum), the no-impact rule, grid insertion and validation messages.
#include <gtest/gtest.h>

#include <limits>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "pathpace/pathpace.hpp"
#include "hand_box.hpp"
#include "test_util.hpp"

using namespace pathpace;
using test::error_of;
using test::hand_on_box;
using test::load;
using test::push_then_brake;
using test::together;

namespace {

// The discrete optimum of push-then-brake (a = F / (m_hand + m_box) = 5): θ = 2as up to the grid point before the
// switch, constant over the two intervals at the switch (there both stances hold: s̈ >= 0 and s̈ <= 0),
// then 2a(2 - s) down to rest.
double push_brake_duration(const Eigen::VectorXd& s, Eigen::Index k_switch, double a = 5.0) {
  Eigen::VectorXd th(s.size());
  for (Eigen::Index k = 0; k < s.size(); ++k) th[k] = std::min(2 * a * s[k], 2 * a * (2.0 - s[k]));
  th[k_switch] = std::min(th[k_switch - 1], th[k_switch + 1]);
  return test::duration_of(s.tail(s.size() - 1) - s.head(s.size() - 1), th);
}

// The hand's force limited to `force` (the hand_x joint; the box's joint unlimited), as TorqueLimits bounds.
struct HandForce {
  Eigen::Index hand;
  Eigen::Vector2d lo, hi;
};
HandForce hand_force(const RobotModel& robot, double force) {
  const auto& names = robot.joint_names();
  HandForce h{std::find(names.begin(), names.end(), "hand_x") - names.begin(), Eigen::Vector2d::Zero(),
              Eigen::Vector2d::Zero()};
  h.lo[h.hand] = -force;
  h.hi[h.hand] = force;
  return h;
}

}  // namespace

TEST(ContactPhases, PushThenBrakeHasTheClosedFormOptimumAndNamesThePhases) {
  auto robot = load("hand_box.urdf");
  TimeScalingProblem prob(together(), 20);
  ContactOptions o;
  o.cone_edges = 4;
  prob.add_contact_phases(robot, push_then_brake(), o);
  ASSERT_EQ(prob.constraints().size(), 2u);
  const Result r = prob.solve();
  ASSERT_EQ(r.status, Status::Optimal) << r.message;
  EXPECT_NEAR(r.duration, push_brake_duration(prob.grid(), 10), 1e-9);
  EXPECT_NEAR(r.sdot[10], std::sqrt(2 * 5.0 * 0.9), 1e-9);  // s̈ = 0 on both intervals at the switch
  // Accelerating intervals bind the hand's force in phase 0, braking ones in phase 1.
  EXPECT_EQ(r.binding[3], "phases[0]: torque hand_x upper");
  EXPECT_EQ(r.binding[16], "phases[1]: torque hand_x lower");
  ASSERT_EQ(r.contact_phases.size(), 2u);
  // Forces per phase: pushing (+5 N on the box) before the switch, braking (-5 N) after; at the switch time the
  // later phase.
  const Trajectory tr = r.trajectory();
  Eigen::VectorXd t(3);
  t << 0.25 * tr.times()[10], tr.times()[10], 0.5 * (tr.times()[10] + tr.duration());
  const Eigen::VectorXi phase = tr.contact_phase(t);
  EXPECT_EQ(phase[0], 0);
  EXPECT_EQ(phase[1], 1);
  EXPECT_EQ(phase[2], 1);
  Eigen::VectorXi used;
  const auto f = tr.contact_forces(t, &used);
  EXPECT_EQ(used, phase);  // the phases that served the forces, from the same evaluation
  EXPECT_NEAR(f[0].forces(0, 0), 5.0, 1e-6);
  EXPECT_NEAR(f[1].forces(0, 0), 0.0, 1e-6);
  EXPECT_NEAR(f[2].forces(0, 0), -5.0, 1e-6);
  EXPECT_GE(f[2].margin, 0.0);
  // Restarted at a grid point with the optimum's speed: the rest of the same timing (phases kept, s̈ = 0
  // at the switch included).
  const TimeScalingProblem tail = prob.restarted(prob.grid()[5], r.sdot[5]);
  const Result rt = tail.solve();
  ASSERT_EQ(rt.status, Status::Optimal) << rt.message;
  EXPECT_NEAR(rt.duration, r.duration - r.times[5], 1e-9);
}

TEST(ContactPhases, ASwitchOffTheGridIsInserted) {
  auto robot = load("hand_box.urdf");
  TimeScalingProblem prob(together(), 7);  // grid points at multiples of 2/7: 1 is not one
  prob.add_velocity_limits(Eigen::Vector2d(-100, -100), Eigen::Vector2d(100, 100));
  prob.add_contact_phases(robot, push_then_brake());
  ASSERT_EQ(prob.intervals(), 8);
  EXPECT_EQ(prob.grid()[4], 1.0);
  const Result r = prob.solve();
  ASSERT_EQ(r.status, Status::Optimal) << r.message;
  EXPECT_NEAR(r.duration, push_brake_duration(prob.grid(), 4), 1e-9);
  // A switch within 1e-9 of the length of a grid point snaps to it (no sliver interval).
  TimeScalingProblem snapped(together(), 20);
  snapped.add_contact_phases(robot, push_then_brake(1.0 + 1e-10));
  EXPECT_EQ(snapped.intervals(), 20);
  EXPECT_EQ(std::dynamic_pointer_cast<const ContactConstraint>(snapped.constraints()[1])->options().active_begin,
            snapped.grid()[10]);
}

// A user's own constraint whose rows are not finite at s = 1 only (a point the grid of 7 intervals lacks).
class BadAtOne : public Constraint {
 public:
  std::string name() const override { return "bad at one"; }
  ConstraintRows evaluate(const PathSamples& samples) const override {
    ConstraintRows r;
    r.resize(samples.size(), 1);
    r.labels = {"bad at one"};
    for (Eigen::Index k = 0; k < samples.size(); ++k) {
      r.a(k, 0) = samples.s[k] == 1.0 ? std::numeric_limits<double>::quiet_NaN() : 1.0;
      r.c(k, 0) = 100.0;
    }
    return r;
  }
};

// The constraints evaluated again at an inserted switch are checked as add_constraint checks them.
TEST(ContactPhases, ConstraintsEvaluatedAtAnInsertedSwitchAreChecked) {
  auto robot = load("hand_box.urdf");
  TimeScalingProblem prob(together(), 7);
  prob.add_constraint(std::make_shared<BadAtOne>());  // finite on the grid of 7 intervals
  const std::string msg = error_of([&] { prob.add_contact_phases(robot, push_then_brake()); });
  EXPECT_NE(msg.find("bad at one"), std::string::npos) << msg;
}

// A path that is not finite at an inserted switch is named as the constructor names it: grid index, s and
// coordinate (the one check of the path's samples).
TEST(ContactPhases, APathNotFiniteAtAnInsertedSwitchIsNamed) {
  auto robot = load("hand_box.urdf");
  auto path = std::make_shared<test::ClosedFormPath>(2, [](double s, auto q, auto dq, auto ddq) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    q << (s == 0.5 ? nan : s), s;  // hand and box together, x = s
    dq << 1.0, 1.0;
    ddq << 0.0, 0.0;
  });
  TimeScalingProblem prob(path, 7);  // finite at the multiples of 1/7; 0.5 is not one
  const std::vector<ContactPhase> ph = {{0.0, 0.5, {hand_on_box(1.0)}, std::nullopt},
                                        {0.5, 1.0, {hand_on_box(-1.0)}, std::nullopt}};
  EXPECT_EQ(error_of([&] { prob.add_contact_phases(robot, ph); }), "path is not finite at grid[4] = 0.5 (coordinate 0)");
  EXPECT_EQ(prob.intervals(), 7);  // nothing changed
  EXPECT_TRUE(prob.constraints().empty());
}

namespace {

// TorqueLimits that count their evaluations.
class CountedTorqueLimits : public TorqueLimits {
 public:
  CountedTorqueLimits(std::shared_ptr<const RobotModel> robot, Eigen::VectorXd lo, Eigen::VectorXd hi, int* calls)
      : TorqueLimits(std::move(robot), std::move(lo), std::move(hi)), calls_(calls) {}
  ConstraintRows evaluate(const PathSamples& samples) const override {
    ++*calls_;
    return TorqueLimits::evaluate(samples);
  }

 private:
  int* calls_;
};

// A user's constraint that counts its evaluations: ṡ² <= 100, which never binds here.
class CountedCap : public Constraint {
 public:
  explicit CountedCap(int* calls) : calls_(calls) {}
  std::string name() const override { return "cap"; }
  ConstraintRows evaluate(const PathSamples& samples) const override {
    ++*calls_;
    ConstraintRows r;
    r.resize(samples.size(), 1);
    r.labels = {"cap"};
    r.a.setOnes();
    r.c.setConstant(100.0);
    return r;
  }

 private:
  int* calls_;
};

}  // namespace

// TorqueLimits that the phases absorb are not evaluated again on a grid with an inserted switch (their rows
// would be dropped); the constraints that stay are, and only then.
TEST(ContactPhases, OnlyTheConstraintsThatStayAreEvaluatedAgainAtAnInsertedSwitch) {
  auto robot = load("hand_box.urdf");
  const auto [hand, lo, hi] = hand_force(*robot, 4.0);
  for (int intervals : {7, 20}) {  // s = 1 is not a grid point of 7 intervals over [0, 2]; it is one of 20
    const bool inserted = intervals == 7;
    int torque_calls = 0, cap_calls = 0;
    TimeScalingProblem prob(together(), intervals);
    prob.add_constraint(std::make_shared<CountedTorqueLimits>(robot, lo, hi, &torque_calls));
    prob.add_constraint(std::make_shared<CountedCap>(&cap_calls));
    ASSERT_EQ(torque_calls, 1);
    ASSERT_EQ(cap_calls, 1);
    prob.add_contact_phases(robot, push_then_brake());
    EXPECT_EQ(prob.intervals(), inserted ? 8 : 20);
    EXPECT_EQ(torque_calls, 1) << intervals;
    EXPECT_EQ(cap_calls, inserted ? 2 : 1) << intervals;
    ASSERT_EQ(prob.constraints().size(), 3u);  // the cap and the two phases, the torque limits merged into them
    for (size_t i = 1; i < 3; ++i)
      EXPECT_EQ(std::dynamic_pointer_cast<const ContactConstraint>(prob.constraints()[i])->tau_max()[hand], 4.0);
    const Result r = prob.solve();
    ASSERT_EQ(r.status, Status::Optimal) << r.message;
    EXPECT_NEAR(r.duration, push_brake_duration(prob.grid(), inserted ? 4 : 10, 2.0), 1e-9) << intervals;
  }
}

TEST(ContactPhases, TorqueLimitsJoinEveryPhaseAddedBeforeOrAfter) {
  // The hand's force limited to 4 N (a = 4 / 2 kg = 2) by a TorqueLimits, before or after the phases.
  auto robot = load("hand_box.urdf");
  const auto [hand, lo, hi] = hand_force(*robot, 4.0);
  for (bool before : {true, false}) {
    TimeScalingProblem prob(together(), 20);
    if (before) prob.add_constraint(std::make_shared<TorqueLimits>(robot, lo, hi));
    prob.add_contact_phases(robot, push_then_brake());
    if (!before) prob.add_constraint(std::make_shared<TorqueLimits>(robot, lo, hi));
    ASSERT_EQ(prob.constraints().size(), 2u) << before;
    for (const auto& c : prob.constraints()) {
      auto contact = std::dynamic_pointer_cast<const ContactConstraint>(c);
      ASSERT_TRUE(contact);
      EXPECT_EQ(contact->tau_max()[hand], 4.0);
    }
    const Result r = prob.solve();
    ASSERT_EQ(r.status, Status::Optimal) << r.message;
    EXPECT_NEAR(r.duration, push_brake_duration(prob.grid(), 10, 2.0), 1e-9) << before;
  }
}

TEST(ContactPhases, InvalidPhasesAreNamed) {
  auto robot = load("hand_box.urdf");
  TimeScalingProblem prob(together(), 20);
  auto ph = push_then_brake();
  EXPECT_EQ(error_of([&] { prob.add_contact_phases(robot, {}); }),
            "phases is empty, expected at least one (s_begin, s_end, contacts)");
  ph[1].s_begin = 1.1;
  EXPECT_EQ(error_of([&] { prob.add_contact_phases(robot, ph); }),
            "phases[1].s_begin = 1.1 must equal phases[0].s_end = 1 (the phases are contiguous)");
  ph = push_then_brake();
  ph[0].s_begin = 0.5;
  EXPECT_EQ(error_of([&] { prob.add_contact_phases(robot, ph); }),
            "phases[0].s_begin = 0.5 must equal the path's s_begin = 0 (the phases cover the path)");
  ph = push_then_brake();
  ph[1].s_end = 1.5;
  EXPECT_EQ(error_of([&] { prob.add_contact_phases(robot, ph); }),
            "phases[1].s_end = 1.5 must equal the path's s_end = 2 (the phases cover the path)");
  ph = {{0.0, 1.0, {hand_on_box(1.0)}, std::nullopt}, {1.0, 1.0, {}, std::nullopt}, {1.0, 2.0, {}, std::nullopt}};
  EXPECT_EQ(error_of([&] { prob.add_contact_phases(robot, ph); }), "phases[1].s_begin = 1 must be < phases[1].s_end = 1");
  ph = push_then_brake();
  ph[1].contacts[0].normal.setZero();
  EXPECT_EQ(error_of([&] { prob.add_contact_phases(robot, ph); }), "phases[1]: contacts[0].normal = (0, 0, 0) must be nonzero");
  EXPECT_TRUE(prob.constraints().empty());  // nothing was added by a failed call
  EXPECT_EQ(prob.intervals(), 20);
  // A per-grid-point linear constraint cannot follow a grid insertion.
  TimeScalingProblem lin(together(), 7);
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(8, 1), one = Eigen::MatrixXd::Ones(8, 1);
  lin.add_linear_constraint(one, zero, zero, -100 * one, 100 * one, "speed cap");
  const std::string msg = error_of([&] { lin.add_contact_phases(robot, push_then_brake(0.9)); });
  EXPECT_NE(msg.find("phases[1].s_begin = 0.9 is not a grid point (nearest: grid[3] = 0.857142857143)"), std::string::npos) << msg;
}

TEST(ContactPhases, PhaseMarginsThatCannotMeetAtTheSwitchAreInfeasibleThere) {
  // Phase 0 demands at least 1 N of push (s̈ >= 1), phase 1 brakes (s̈ <= 0): no s̈ at the switch serves both.
  auto robot = load("hand_box.urdf");
  TimeScalingProblem prob(together(), 20);
  auto ph = push_then_brake();
  ContactOptions strict;
  strict.min_normal_force = 1.0;
  ph[0].options = strict;
  prob.add_contact_phases(robot, ph);
  const Result r = prob.solve();
  ASSERT_EQ(r.status, Status::Infeasible) << r.message;
  EXPECT_EQ(r.infeasibility.grid_index, 10);
  EXPECT_NE(r.message.find("phases["), std::string::npos) << r.message;
}

namespace {

// The foot comes down on s in [0, 1] (z = 1 - s, or (1 - s)² to arrive at rest) and stays on the ground,
// or (reversed) stands and lifts off; the arm moves x = s throughout.
std::shared_ptr<Path> foot_path(const RobotModel& robot, int landing) {
  const auto& names = robot.joint_names();
  const Eigen::Index z = std::find(names.begin(), names.end(), "foot_z") - names.begin();
  const Eigen::Index x = 1 - z;
  std::vector<Eigen::MatrixXd> coef(2, Eigen::MatrixXd::Zero(3, 2));
  coef[0](1, x) = coef[1](1, x) = 1.0;
  coef[1](0, x) = 1.0;
  if (landing == 1) {         // lands moving down at 1 per unit s
    coef[0](0, z) = 1.0;
    coef[0](1, z) = -1.0;
  } else if (landing == 2) {  // lands at rest: z = (1 - s)²
    coef[0](0, z) = 1.0;
    coef[0](1, z) = -2.0;
    coef[0](2, z) = 1.0;
  } else {                    // lifts off at 1 per unit s: z = s - 1 after the switch
    coef[1](1, z) = 1.0;
  }
  return std::make_shared<PiecewisePolynomialPath>(Eigen::Vector3d(0, 1, 2), coef);
}

Result foot_solve(int landing, std::string* rest_label = nullptr, FeasibleSet* at_switch = nullptr) {
  auto robot = load("foot_arm.urdf");
  Contact sole;
  sole.link = "foot";
  std::vector<ContactPhase> ph = {{0.0, 1.0, {}, std::nullopt}, {1.0, 2.0, {sole}, std::nullopt}};
  if (landing == 0) std::swap(ph[0].contacts, ph[1].contacts);
  TimeScalingProblem prob(foot_path(*robot, landing), 20);
  prob.add_contact_phases(robot, ph);
  if (rest_label)
    *rest_label = std::dynamic_pointer_cast<const ContactConstraint>(prob.constraints()[1])->options().rest_at_begin;
  if (at_switch) *at_switch = prob.feasible_set(10);
  return prob.solve();
}

}  // namespace

TEST(ContactPhases, AContactMadeMovingAlongItsNormalStopsThePath) {
  std::string label;
  FeasibleSet fs;
  const Result hit = foot_solve(1, &label, &fs);
  ASSERT_EQ(hit.status, Status::Optimal) << hit.message;
  EXPECT_EQ(hit.sdot[10], 0.0);
  EXPECT_GT(hit.sdot[9], 0.1);
  EXPECT_EQ(label, "no impact: contact 0 (link 'foot') is made at s = 1 moving along its normal (n.c'(s) = -1 m per unit s): "
                   "sdot = 0 there");
  EXPECT_EQ(fs.x_max, 0.0);
  EXPECT_EQ(fs.x_max_label, "phases[1]: " + label);
  // Arriving at rest along the normal, or breaking contact while moving: nothing forces a stop.
  const Result soft = foot_solve(2, &label);
  ASSERT_EQ(soft.status, Status::Optimal) << soft.message;
  EXPECT_EQ(label, "");
  EXPECT_GT(soft.sdot[10], 0.1);
  const Result lift = foot_solve(0, &label);
  ASSERT_EQ(lift.status, Status::Optimal) << lift.message;
  EXPECT_EQ(label, "");
  EXPECT_GT(lift.sdot[10], 0.1);
}

TEST(ContactPhases, PhaseOfSTakesTheLaterAtASwitchAndTheNearestOutsideAndNamesBadInput) {
  auto robot = load("hand_box.urdf");
  auto phase = [&](double a, double b) {
    ContactOptions o;
    o.cone_edges = 4;
    o.active_begin = a;
    o.active_end = b;
    return std::make_shared<const ContactConstraint>(robot, std::vector<Contact>{hand_on_box(1.0)}, o);
  };
  const std::vector<std::shared_ptr<const ContactConstraint>> two{phase(0.0, 1.0), phase(1.0, 2.0)};
  Eigen::VectorXd s(8);
  // Before all, inside, just before the switch (beyond 1e-12), at it (and within 1e-12 either side), after all.
  s << -0.5, 0.5, 1.0 - 1e-9, 1.0 - 4e-13, 1.0, 1.0 + 4e-13, 2.0, 3.0;
  Eigen::VectorXi want(8);
  want << 0, 0, 0, 1, 1, 1, 1, 1;
  EXPECT_EQ(contact_phase_of_s(two, s), want);
  // A gap: the nearest phase, the later one on a tie.
  const std::vector<std::shared_ptr<const ContactConstraint>> gap{phase(0.0, 1.0), phase(2.0, 3.0)};
  Eigen::VectorXd g(3);
  g << 1.4, 1.5, 1.6;
  EXPECT_EQ(contact_phase_of_s(gap, g), Eigen::Vector3i(0, 1, 1));
  EXPECT_EQ(error_of([&] { contact_phase_of_s({}, s); }), "phases is empty, expected at least one ContactConstraint");
  EXPECT_EQ(error_of([&] { contact_phase_of_s({two[0], nullptr}, s); }), "phases[1] is null, expected a ContactConstraint");
  EXPECT_EQ(error_of([&] { contact_phase_of_s({two[1], two[0]}, s); }),
            "phases[1].active_begin = 0 must be >= phases[0].active_begin = 1 (phases in order of s)");
  s[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of([&] { contact_phase_of_s(two, s); }), "s[2] = nan must be finite");
  EXPECT_EQ(error_of([&] { phase(2.0, 1.0); }), "active_begin = 2 must be <= active_end = 1");
}
