#include "pathpace/contact_wrenches.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/trajectory.hpp"

namespace pathpace {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every link on either side of a contact, in first-appearance order over the constraints.
std::vector<std::string> contact_links(const std::vector<std::shared_ptr<const ContactConstraint>>& cons) {
  std::vector<std::string> links;
  auto add = [&links](const std::string& name) {
    if (!name.empty() && std::find(links.begin(), links.end(), name) == links.end()) links.push_back(name);
  };
  for (const auto& con : cons)
    for (const Contact& c : con->contacts()) {
      add(c.link);
      add(c.other_link);
    }
  return links;
}

// One link's running sums at one sample.
struct LinkSums {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero(), cop = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double normal_force = 0.0, scale = 0.0;
  bool one_normal = true, any = false;

  void add(const Eigen::Vector3d& p, const Eigen::Vector3d& origin, const Eigen::Vector3d& n, const Eigen::Vector3d& f) {
    if (any && (n - normal).norm() > 1e-9) one_normal = false;
    normal = n;
    any = true;
    force += f;
    moment += (p - origin).cross(f);
    const double fn = n.dot(f);
    normal_force += fn;
    cop += fn * p;
    scale += f.norm();
  }
};

}  // namespace

ContactWrenches Trajectory::contact_wrenches(const Eigen::Ref<const Eigen::VectorXd>& t,
                                             ForceDistribution distribution) const {
  Eigen::VectorXi phase;
  const std::vector<ContactForces> forces = contact_forces(t, &phase, distribution);  // throws without contacts
  std::vector<std::shared_ptr<const ContactConstraint>> cons = contact_phases_;
  if (cons.empty()) cons.push_back(contacts_);
  Eigen::MatrixXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  ContactWrenches out;
  out.links = contact_links(cons);
  const Eigen::Index m = t.size(), L = static_cast<Eigen::Index>(out.links.size());
  out.force.setZero(m, 3 * L);
  out.moment.setZero(m, 3 * L);
  out.center_of_pressure.setConstant(m, 3 * L, kNaN);
  out.normal_force.setZero(m, L);
  // The LP's verdict on the very forces summed here, so that a plot of the totals needs no second solve.
  out.margin.resize(m);
  out.feasible.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    out.margin[i] = forces[static_cast<size_t>(i)].margin;
    out.feasible[i] = forces[static_cast<size_t>(i)].feasible;
  }
  out.phase = std::move(phase);
  std::map<std::string, Eigen::Index> column;
  for (Eigen::Index l = 0; l < L; ++l) column[out.links[static_cast<size_t>(l)]] = l;
  for (Eigen::Index i = 0; i < m; ++i) {
    const ContactForces& cf = forces[static_cast<size_t>(i)];
    if (!cf.feasible) {
      out.force.row(i).setConstant(kNaN);
      out.moment.row(i).setConstant(kNaN);
      out.normal_force.row(i).setConstant(kNaN);
      continue;
    }
    const ContactConstraint& con = *cons[static_cast<size_t>(out.phase[i] < 0 ? 0 : out.phase[i])];
    const RobotModel& robot = *con.robot();
    const Eigen::VectorXd qi = q.row(i).transpose();
    std::map<std::string, Eigen::Matrix4d> placement;  // each link's once per sample
    auto X = [&](const std::string& link) -> const Eigen::Matrix4d& {
      auto it = placement.find(link);
      if (it == placement.end()) it = placement.emplace(link, robot.frame_placement(qi, link)).first;
      return it->second;
    };
    std::vector<LinkSums> sums(static_cast<size_t>(L));
    for (size_t j = 0; j < con.contacts().size(); ++j) {
      const Contact& c = con.contacts()[j];
      const Eigen::Matrix4d& Xl = X(c.link);
      const Eigen::Vector3d p = Xl.topLeftCorner<3, 3>() * c.point + Xl.topRightCorner<3, 1>();
      // The normal is into `link`: world coordinates, or other_link's frame (it turns with that link).
      Eigen::Vector3d n = c.normal.normalized();
      if (!c.other_link.empty()) n = X(c.other_link).topLeftCorner<3, 3>() * n;
      const Eigen::Vector3d f = cf.forces.row(static_cast<Eigen::Index>(j)).transpose();
      sums[static_cast<size_t>(column[c.link])].add(p, Xl.topRightCorner<3, 1>(), n, f);
      if (!c.other_link.empty())
        sums[static_cast<size_t>(column[c.other_link])].add(p, X(c.other_link).topRightCorner<3, 1>(), -n, -f);
    }
    for (Eigen::Index l = 0; l < L; ++l) {
      const LinkSums& k = sums[static_cast<size_t>(l)];
      out.force.block<1, 3>(i, 3 * l) = k.force.transpose();
      out.moment.block<1, 3>(i, 3 * l) = k.moment.transpose();
      out.normal_force(i, l) = k.normal_force;
      // A centre of pressure needs one contact plane's normal and a push along it (not a rounding-level one).
      if (k.any && k.one_normal && k.normal_force > 1e-12 * std::max(1.0, k.scale))
        out.center_of_pressure.block<1, 3>(i, 3 * l) = (k.cop / k.normal_force).transpose();
    }
  }
  return out;
}

}  // namespace pathpace
