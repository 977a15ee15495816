#pragma once
/// @file contact.hpp
/// A frictional point contact of a robot link with the world or with another link (sec. III.b).

#include <string>

#include <Eigen/Core>

namespace pathpace {

// docstrings.txt @@ Contact
/// @brief A point contact with Coulomb friction: a point fixed in a link (link coordinates) touching the world, or
/// `other_link` when given.
///
/// Robot–robot: two links of one model, e.g. a hand on a free object. `normal` points into `link`, the
/// direction in which the other side can push it: in world coordinates for a world contact, in
/// `other_link`'s frame for a robot–robot contact (it turns with that link). The other side feels the
/// opposite force at the same point. The normal is normalised on use (zero is rejected).
struct Contact {
  std::string link;
  // docstrings.txt @@ Contact.point
  /// (3,): m, link frame.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double friction = 0.5;
  std::string other_link;  ///< empty: the world
};

}  // namespace pathpace
