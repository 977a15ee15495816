// A constraint family defined only here (issue 26): a per-joint speed bound |q̇_j| <= v_j(s) that varies
// along the path, written as eq. (16)'s bound x <= (v_j(s) / p'_j)². Through Constraint's hooks alone it must
// give its own optimum, compose with torque limits and contacts, be carried by restarted(), be refused
// where rows given per grid point cannot follow a grid change, and be relaxed by relaxation(); a subclass
// of TorqueLimits defined here must still join a contact constraint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "pathpace/pathpace.hpp"
#include "hand_box.hpp"
#include "test_util.hpp"

using namespace pathpace;
using namespace pathpace::test;  // error_of, duration_of, ClosedFormPath, the hand-and-box helpers

namespace {

using Profile = std::function<double(double)>;

// |q̇_j| <= v_j · g(s): one row per joint, a = 1, b = 0, c = (v_j g(s) / |p'_j|)² (none where p'_j = 0), the
// same arithmetic as VelocityLimits, so that g = 1 gives its rows bit for bit.
class SpeedProfile : public Constraint {
 public:
  SpeedProfile(Eigen::VectorXd v, Profile g, std::vector<std::string> names = {}, bool relaxable = true)
      : v_(std::move(v)), g_(std::move(g)), names_(std::move(names)), relaxable_(relaxable) {}
  std::string name() const override { return "speed profile"; }
  ConstraintRows evaluate(const PathSamples& samples) const override {
    if (samples.dof() != v_.size()) throw InvalidInput("speed profile: path has the wrong number of coordinates");
    ConstraintRows rows;
    rows.resize(samples.size(), v_.size());
    for (Eigen::Index j = 0; j < v_.size(); ++j) {
      rows.labels[static_cast<size_t>(j)] = "speed " + (names_.empty() ? "joint " + std::to_string(j) : names_[j]);
      for (Eigen::Index k = 0; k < samples.size(); ++k) {
        const double d = std::abs(samples.dq(k, j)), r = v_[j] * g_(samples.s[k]) / d;
        if (d == 0.0) continue;  // the joint does not move here: no bound (c stays +inf)
        rows.a(k, j) = 1.0;
        rows.c(k, j) = r * r;
      }
    }
    return rows;
  }
  std::string family() const override { return relaxable_ ? "speed" : ""; }
  std::shared_ptr<const Constraint> relaxed(double scale) const override {
    return relaxable_ ? std::make_shared<SpeedProfile>(v_ * scale, g_, names_) : nullptr;
  }
  std::shared_ptr<const Constraint> with_joint_names(const std::vector<std::string>& names) const override {
    return names_.empty() ? std::make_shared<SpeedProfile>(v_, g_, names, relaxable_) : nullptr;
  }

 private:
  Eigen::VectorXd v_;
  Profile g_;
  std::vector<std::string> names_;
  bool relaxable_;
};

// The same bound given per grid point (a table of the profile's rows on one grid): the problem may not move
// its grid points (per_grid_point), and a restart keeps the rows of the points it keeps (at_grid_points).
class SpeedTable : public Constraint {
 public:
  explicit SpeedTable(ConstraintRows rows) : rows_(std::move(rows)) {}
  std::string name() const override { return "speed table"; }
  ConstraintRows evaluate(const PathSamples& samples) const override {
    if (samples.size() != rows_.a.rows()) throw InvalidInput("speed table: rows for another grid");
    ConstraintRows r = rows_;
    r.valid_by_construction = false;
    return r;
  }
  bool per_grid_point() const override { return true; }
  std::shared_ptr<const Constraint> at_grid_points(const std::vector<Eigen::Index>& kept) const override {
    ConstraintRows r;
    r.resize(static_cast<Eigen::Index>(kept.size()), rows_.rows());
    r.labels = rows_.labels;
    for (size_t i = 0; i < kept.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      r.a.row(k) = rows_.a.row(kept[i]);
      r.b.row(k) = rows_.b.row(kept[i]);
      r.c.row(k) = rows_.c.row(kept[i]);
    }
    return std::make_shared<SpeedTable>(std::move(r));
  }

 private:
  ConstraintRows rows_;
};

// Torque limits under another name: a subclass of the library's TorqueLimits, defined here.
class NamedTorque : public TorqueLimits {
 public:
  using TorqueLimits::TorqueLimits;
  std::string name() const override { return "named torque"; }
};

// p(s) = (s, s² / 2) on [0, 1]: p' = (1, s), so joint 1 bounds nothing at s = 0 and joint 0 or 1 binds
// depending on the profile.
std::shared_ptr<Path> bend() {
  return std::make_shared<test::ClosedFormPath>(2, [](double s, auto q, auto dq, auto ddq) {
    q << s, 0.5 * s * s;
    dq << 1.0, s;
    ddq << 0.0, 1.0;
  });
}

double g_rising(double s) { return 1.0 + s * s; }

// The optimum of a bound on x alone (no bound on s̈): each grid point at its largest x, the ends at the
// boundary speeds (eq. 27). x_k = min_j (v_j g(s_k) / |p'_j(s_k)|)².
double speed_only_duration(const Eigen::VectorXd& s, const Eigen::VectorXd& v, const Profile& g, double x_begin = 0.0,
                           double x_end = 0.0) {
  const Eigen::Index n = s.size() - 1;
  Eigen::VectorXd x(n + 1);
  for (Eigen::Index k = 0; k <= n; ++k) {
    const double d[2] = {1.0, s[k]};
    x[k] = std::numeric_limits<double>::infinity();
    for (int j = 0; j < 2; ++j)
      if (d[j] != 0.0) x[k] = std::min(x[k], std::pow(v[j] * g(s[k]) / d[j], 2));
  }
  x[0] = x_begin;
  x[n] = x_end;
  return test::duration_of(s.tail(n) - s.head(n), x);
}

// hand_box.urdf with the hand's force within ±4 N, the box's joint unactuated (a = 4 N / 2 kg = 2 while pushing or
// braking), and a speed cap v² g(s)² = 2 + 0.5 min(s, 2 - s): rising while pushing, falling while braking, slower
// than 2a = 4.
struct HandBoxCase {
  std::shared_ptr<RobotModel> robot = load("hand_box.urdf");
  Eigen::Index hand = std::find(robot->joint_names().begin(), robot->joint_names().end(), "hand_x") -
                      robot->joint_names().begin();
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();
  Eigen::Vector2d v = Eigen::Vector2d::Constant(std::sqrt(2.0));
  Profile g = [](double s) { return std::sqrt((2.0 + 0.5 * std::min(s, 2.0 - s)) / 2.0); };
  HandBoxCase() { lo[hand] = -4.0, hi[hand] = 4.0; }
  double cap(double s) const { return std::pow(v[0] * g(s), 2); }
};

// Push-then-brake under |s̈| <= a, s̈ >= 0 while pushing, <= 0 while braking, and x <= cap(s): the largest
// profile is min(2as, 2a(2 - s), cap(s)) when cap rises (falls) no faster than 2a on the push (brake) stretch,
// and at the switch (both stances hold: s̈ = 0 on both intervals there) the smaller of its neighbours.
double push_brake_capped(const Eigen::VectorXd& s, Eigen::Index k_switch, double a, const Profile& cap) {
  Eigen::VectorXd th(s.size());
  for (Eigen::Index k = 0; k < s.size(); ++k) th[k] = std::min({2 * a * s[k], 2 * a * (2.0 - s[k]), cap(s[k])});
  th[k_switch] = std::min(th[k_switch - 1], th[k_switch + 1]);
  return test::duration_of(s.tail(s.size() - 1) - s.head(s.size() - 1), th);
}

Result solved(const TimeScalingProblem& p) {
  Result r = p.solve();
  EXPECT_EQ(r.status, Status::Optimal) << r.message;
  return r;
}

}  // namespace

// (a) Alone: the closed-form optimum of a bound on x alone, and with g = 1 the VelocityLimits optimum bit for
// bit (the same rows through the same solver; no tolerance is involved).
TEST(ConstraintHooks, ATestFamilyAloneHasItsClosedFormOptimum) {
  const Eigen::Vector2d v(1.0, 0.6);
  TimeScalingProblem prob(bend(), 40);
  prob.add_constraint(std::make_shared<SpeedProfile>(v, g_rising));
  ASSERT_EQ(prob.constraints().size(), 1u);
  const Result r = solved(prob);
  const double T = speed_only_duration(prob.grid(), v, g_rising);
  EXPECT_NEAR(r.duration, T, 1e-9 * T);
  // x_max at s = 1: joint 1 binds there ((0.6 · 2 / 1)² = 1.44 < (1 · 2 / 1)² = 4), labelled by the family.
  const FeasibleSet end = prob.feasible_set(40);
  EXPECT_NEAR(end.x_max, 1.44, 1e-12);
  EXPECT_EQ(end.x_max_label, "speed joint 1");

  TimeScalingProblem constant(bend(), 40), builtin(bend(), 40);
  constant.add_constraint(std::make_shared<SpeedProfile>(v, [](double) { return 1.0; }));
  builtin.add_velocity_limits(-v, v);
  const Result rc = solved(constant), rb = solved(builtin);
  EXPECT_EQ(rc.duration, rb.duration);
  EXPECT_EQ(rc.sdot, rb.sdot);
  EXPECT_NE(rc.duration, r.duration);  // the profile matters
}

// with_joint_names: names set after the family was added reach its labels.
TEST(ConstraintHooks, ATestFamilyTakesTheProblemsJointNames) {
  TimeScalingProblem prob(bend(), 10);
  prob.add_constraint(std::make_shared<SpeedProfile>(Eigen::Vector2d(1.0, 0.6), g_rising));
  prob.set_joint_names({"x", "y"});
  EXPECT_EQ(prob.feasible_set(10).x_max_label, "speed y");
}

// (b) With torque limits (a pendulum): both kept side by side, the result shows the torque limits, T is no less
// than either alone, and with g = 1 it is the T of torque + VelocityLimits bit for bit.
TEST(ConstraintHooks, ATestFamilyComposesWithTorqueLimits) {
  auto pendulum = load("pendulum.urdf");
  auto swing = std::make_shared<test::ClosedFormPath>(1, [](double s, auto q, auto dq, auto ddq) {
    q << 0.5 * s;  // to 0.5 rad: held at rest there (9.81 sin 0.5 = 4.7 < 5.6 N m)
    dq << 0.5;
    ddq << 0.0;
  });
  const Eigen::VectorXd v = Eigen::VectorXd::Constant(1, 0.5);  // x <= g(s)²: binds mid-swing
  auto torque = std::make_shared<TorqueLimits>(pendulum);
  auto both = [&](std::shared_ptr<const Constraint> speed) {
    TimeScalingProblem p(swing, 50);
    p.add_constraint(torque);
    if (speed) p.add_constraint(std::move(speed));
    return p;
  };
  const TimeScalingProblem with = both(std::make_shared<SpeedProfile>(v, g_rising));
  ASSERT_EQ(with.constraints().size(), 2u);
  EXPECT_EQ(with.constraints()[1]->name(), "speed profile");
  TimeScalingProblem alone(swing, 50);
  alone.add_constraint(std::make_shared<SpeedProfile>(v, g_rising));
  const Result r = solved(with), rt = solved(both(nullptr)), rs = solved(alone);
  EXPECT_EQ(r.robot, pendulum);
  EXPECT_EQ(r.tau_max, torque->tau_max());
  EXPECT_FALSE(r.contacts);
  // Each binds somewhere: T is above both (by far more than the solver's tolerance).
  EXPECT_GT(r.duration, rt.duration * (1 + 1e-3));
  EXPECT_GT(r.duration, rs.duration * (1 + 1e-3));

  TimeScalingProblem builtin = both(nullptr);
  builtin.add_velocity_limits(-v, v);
  const Result rc = solved(both(std::make_shared<SpeedProfile>(v, [](double) { return 1.0; }))), rb = solved(builtin);
  EXPECT_EQ(rc.duration, rb.duration);
  EXPECT_EQ(rc.sdot, rb.sdot);
}

// (b) With contact phases and torque limits (hand_box): the torque limits merge into every phase as before, the
// family stays a constraint of its own, the result shows robot, torque limits and phases, and T is the closed
// form of push-then-brake under the speed cap, above the T without it.
TEST(ConstraintHooks, ATestFamilyComposesWithContactPhasesAndTorque) {
  const HandBoxCase hb;
  for (bool speed_first : {true, false}) {
    TimeScalingProblem prob(together(), 20), without(together(), 20);
    if (speed_first) prob.add_constraint(std::make_shared<SpeedProfile>(hb.v, hb.g));
    prob.add_contact_phases(hb.robot, push_then_brake());
    prob.add_constraint(std::make_shared<TorqueLimits>(hb.robot, hb.lo, hb.hi));
    if (!speed_first) prob.add_constraint(std::make_shared<SpeedProfile>(hb.v, hb.g));
    without.add_contact_phases(hb.robot, push_then_brake());
    without.add_constraint(std::make_shared<TorqueLimits>(hb.robot, hb.lo, hb.hi));
    ASSERT_EQ(prob.constraints().size(), 3u) << speed_first;
    int phases = 0, speeds = 0;
    for (const auto& c : prob.constraints()) {
      if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(c)) {
        ++phases;
        EXPECT_EQ(contact->tau_max()[hb.hand], 4.0);
      }
      speeds += c->name() == "speed profile";
    }
    EXPECT_EQ(phases, 2);
    EXPECT_EQ(speeds, 1);
    const Result r = solved(prob), r0 = solved(without);
    EXPECT_EQ(r.robot, hb.robot);
    ASSERT_EQ(r.tau_max.size(), 2);
    EXPECT_EQ(r.tau_max[hb.hand], 4.0);
    EXPECT_TRUE(r.contacts);
    EXPECT_EQ(r.contact_phases.size(), 2u);
    const auto cap = [&](double s) { return hb.cap(s); };
    EXPECT_NEAR(r.duration, push_brake_capped(prob.grid(), 10, 2.0, cap), 1e-9) << speed_first;
    EXPECT_NEAR(r0.duration, push_brake_capped(prob.grid(), 10, 2.0, [](double) { return INFINITY; }), 1e-9);
    EXPECT_GT(r.duration, r0.duration * (1 + 1e-3));
  }
}

// (b) A switch off the grid is inserted, and the family is evaluated again on the new grid (its cap at the
// inserted s = 1 is in the closed form); the same family given per grid point refuses the insertion.
TEST(ConstraintHooks, AContactSwitchReevaluatesTheFamilyAndIsRefusedByRowsPerGridPoint) {
  const HandBoxCase hb;
  TimeScalingProblem prob(together(), 7);  // grid points at multiples of 2/7: 1 is not one
  prob.add_constraint(std::make_shared<SpeedProfile>(hb.v, hb.g));
  prob.add_constraint(std::make_shared<TorqueLimits>(hb.robot, hb.lo, hb.hi));
  prob.add_contact_phases(hb.robot, push_then_brake());
  ASSERT_EQ(prob.intervals(), 8);
  ASSERT_EQ(prob.grid()[4], 1.0);
  const Result r = solved(prob);
  const auto cap = [&](double s) { return hb.cap(s); };
  EXPECT_NEAR(r.duration, push_brake_capped(prob.grid(), 4, 2.0, cap), 1e-9);

  TimeScalingProblem table(together(), 7);
  table.add_constraint(std::make_shared<SpeedTable>(SpeedProfile(hb.v, hb.g).evaluate(table.samples())));
  EXPECT_EQ(error_of([&] { table.add_contact_phases(hb.robot, push_then_brake()); }),
            "phases[1].s_begin = 1 is not a grid point (nearest: grid[4] = 1.14285714286) and the problem has a "
            "constraint given per grid point ('speed table') that cannot be evaluated on a new grid: add the contact "
            "phases first, or use a grid with a point at every switch");
  EXPECT_EQ(table.intervals(), 7);  // unchanged
}

// (c) restarted() carries the family, evaluated again on the new grid (s0 off the old grid gets its own bound);
// the per-grid-point variant restarts at a grid point with the rows kept there, and refuses any other s0.
TEST(ConstraintHooks, RestartCarriesTheFamilyAndRowsPerGridPointNeedAGridPoint) {
  const Eigen::Vector2d v(1.0, 0.6);
  TimeScalingProblem prob(bend(), 40);
  prob.add_constraint(std::make_shared<SpeedProfile>(v, g_rising));
  prob.set_boundary_speeds(0.0, 0.5);
  const double s0 = 0.4321, sdot0 = 0.7;  // s0 between grid points 17 and 18
  const TimeScalingProblem tail = prob.restarted(s0, sdot0);
  ASSERT_EQ(tail.constraints().size(), 1u);
  EXPECT_EQ(tail.constraints()[0]->name(), "speed profile");
  ASSERT_EQ(tail.grid()[0], s0);
  const Result rt = solved(tail);
  const double T = speed_only_duration(tail.grid(), v, g_rising, sdot0 * sdot0, 0.25);
  EXPECT_NEAR(rt.duration, T, 1e-9 * T);
  // ṡ0 above the bound at s0 (x <= (1 + s0²)² there): the new grid's first point has the family's rows.
  const double x0 = std::pow(1.0 + s0 * s0, 2);
  EXPECT_EQ(prob.restarted(s0, std::sqrt(x0) * 1.01).solve().status, Status::Infeasible);
  EXPECT_EQ(prob.restarted(s0, std::sqrt(x0) * 0.99).solve().status, Status::Optimal);

  TimeScalingProblem table(bend(), 40);
  table.add_constraint(std::make_shared<SpeedTable>(SpeedProfile(v, g_rising).evaluate(table.samples())));
  table.set_boundary_speeds(0.0, 0.5);
  EXPECT_EQ(error_of([&] { table.restarted(s0, sdot0); }),
            "restarted: s0 = 0.4321 is not a grid point (nearest: grid[17] = 0.425) and constraint 'speed table' is "
            "given per grid point (no value between grid points): restart at a grid point");
  const TimeScalingProblem at_grid = table.restarted(table.grid()[17], sdot0), same = prob.restarted(prob.grid()[17], sdot0);
  ASSERT_EQ(at_grid.intervals(), 23);
  EXPECT_EQ(at_grid.constraints()[0]->name(), "speed table");
  const Result ra = solved(at_grid), rs = solved(same);
  EXPECT_EQ(ra.duration, rs.duration);  // the kept rows are the profile's on those points
  EXPECT_EQ(ra.sdot, rs.sdot);
}

// (d) A subclass of TorqueLimits defined here still joins every contact phase, added before or after them.
TEST(ConstraintHooks, ASubclassOfTorqueLimitsMergesIntoContacts) {
  const HandBoxCase hb;
  auto named = std::make_shared<NamedTorque>(hb.robot, hb.lo, hb.hi);
  TimeScalingProblem before(together(), 20), after(together(), 20);
  before.add_constraint(named);
  before.add_contact_phases(hb.robot, push_then_brake());
  after.add_contact_phases(hb.robot, push_then_brake());
  after.add_constraint(named);
  for (const TimeScalingProblem* prob : {&before, &after}) {
    const auto& cs = prob->constraints();
    ASSERT_EQ(cs.size(), 2u);
    const auto first = std::dynamic_pointer_cast<const ContactConstraint>(cs[0]);
    const auto second = std::dynamic_pointer_cast<const ContactConstraint>(cs[1]);
    ASSERT_TRUE(first && second);
    EXPECT_EQ(first->tau_max()[hb.hand], 4.0);
    EXPECT_EQ(second->tau_min()[hb.hand], -4.0);
    EXPECT_NEAR(solved(*prob).duration, push_brake_capped(prob->grid(), 10, 2.0, [](double) { return INFINITY; }), 1e-9);
  }
  // A single contact constraint (add_constraint) takes it too.
  TimeScalingProblem one(together(), 20);
  auto push = std::make_shared<ContactConstraint>(hb.robot, std::vector<Contact>{hand_on_box(1.0)});
  one.add_constraint(push);
  one.add_constraint(std::make_shared<NamedTorque>(hb.robot, hb.lo, hb.hi));
  ASSERT_EQ(one.constraints().size(), 1u);
  EXPECT_EQ(std::dynamic_pointer_cast<const ContactConstraint>(one.constraints()[0])->tau_max()[hb.hand], 4.0);
}

// (e) relaxation() scales the family by its family() and relaxed(): ṡ0 = 3 x the bound at s = 0 needs the
// speeds x 3; a family that declares none is not relaxed.
TEST(ConstraintHooks, RelaxationScalesTheFamily) {
  const Eigen::Vector2d v(1.0, 0.6);
  for (bool relaxable : {true, false}) {
    TimeScalingProblem prob(bend(), 20);
    prob.add_constraint(std::make_shared<SpeedProfile>(v, g_rising, std::vector<std::string>{}, relaxable));
    prob.set_boundary_speeds(3.0, 0.0);  // x <= (1 · g(0) / 1)² = 1 at s = 0
    ASSERT_EQ(prob.solve().status, Status::Infeasible);
    const std::map<std::string, double> m = prob.relaxation(1e3, 1e-3);
    if (!relaxable) {
      EXPECT_TRUE(m.empty());
      continue;
    }
    ASSERT_EQ(m.size(), 1u);
    ASSERT_EQ(m.count("speed"), 1u);
    EXPECT_GE(m.at("speed"), 3.0 * (1 - 1e-12));
    EXPECT_LE(m.at("speed"), 3.0 * (1 + 1e-3) * (1 + 1e-12));
  }
}

// speed_bounds_between_grid_points: guarantee = continuous adds a constraint's bounds as rows x <= bound
// (the grid guarantee does not), named after its first row; a wrong count or a bound that is not a number
// >= 0 is an InvalidInput naming the constraint.
namespace {

class CappedProfile : public SpeedProfile {
 public:
  CappedProfile(Eigen::VectorXd v, std::function<Eigen::VectorXd(const PathSamples&)> bounds)
      : SpeedProfile(std::move(v), [](double) { return 1.0; }), bounds_(std::move(bounds)) {}
  Eigen::VectorXd speed_bounds_between_grid_points(const PathSamples& samples, const ConstraintRows&) const override {
    return bounds_(samples);
  }

 private:
  std::function<Eigen::VectorXd(const PathSamples&)> bounds_;
};

}  // namespace

TEST(ConstraintHooks, SpeedBoundsBetweenGridPointsBecomeRowsUnderTheContinuousGuarantee) {
  const Eigen::Vector2d v(1.0, 0.6);
  SolverOptions continuous;
  continuous.guarantee = Guarantee::Continuous;
  TimeScalingProblem prob(bend(), 40);
  prob.add_constraint(std::make_shared<CappedProfile>(v, [](const PathSamples& s) {
    return Eigen::VectorXd::Constant(s.size(), 0.04);  // ṡ <= 0.2 everywhere
  }));
  const Result grid = prob.solve(), cont = prob.solve(continuous);
  ASSERT_TRUE(grid.ok() && cont.ok());
  EXPECT_GT(grid.sdot.maxCoeff(), 0.3);
  EXPECT_LE(cont.sdot.maxCoeff(), 0.2 * (1 + 1e-12));
  EXPECT_NEAR(cont.sdot.maxCoeff(), 0.2, 1e-9);
  bool named = false;
  for (size_t k = 0; k < cont.binding.size(); ++k)
    named = named || cont.binding[k] == "speed joint 0 (between grid points)";
  EXPECT_TRUE(named);

  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    TimeScalingProblem p(bend(), 10);
    p.add_constraint(std::make_shared<CappedProfile>(v, [bad](const PathSamples& s) {
      Eigen::VectorXd b = Eigen::VectorXd::Constant(s.size(), 1.0);
      b[3] = bad;
      return b;
    }));
    EXPECT_NE(error_of([&] { p.solve(continuous); }).find("speed profile: speed_bounds_between_grid_points gave"),
              std::string::npos);
  }
  TimeScalingProblem p(bend(), 10);
  p.add_constraint(std::make_shared<CappedProfile>(v, [](const PathSamples&) { return Eigen::VectorXd::Ones(3); }));
  EXPECT_EQ(error_of([&] { p.solve(continuous); }),
            "speed profile: speed_bounds_between_grid_points gave 3 bounds for 11 grid points");
}
