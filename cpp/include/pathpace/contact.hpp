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
  // docstrings.txt @@ Contact.link
  /// The link that touches.
  std::string link;
  // docstrings.txt @@ Contact.point
  /// (3,): m, link frame.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  // docstrings.txt @@ Contact.normal
  /// (3,): Into `link`: world coordinates for a world contact, other_link's frame otherwise.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  // docstrings.txt @@ Contact.friction
  /// Coulomb coefficient μ.
  double friction = 0.5;
  // docstrings.txt @@ Contact.other_link
  /// The other body of a robot–robot contact; None (C++: empty): the world.
  std::string other_link;
};

}  // namespace pathpace
