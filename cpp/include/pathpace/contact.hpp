#pragma once
/// @file contact.hpp
/// A frictional point contact of a robot link with the world or with another link (sec. III.b).

#include <string>

#include <Eigen/Core>

namespace pathpace {

/// A point fixed in `link` (coordinates in the link frame) touching the world, or touching
/// `other_link` when that is set (robot–robot: two links of one model, e.g. a hand on a free object).
/// `normal` points into `link`, the direction in which the other side can push it: in world coordinates
/// for a world contact, in `other_link`'s frame for a robot–robot contact (it turns with that link).
/// The other side feels the opposite force at the same point. `friction` is the Coulomb coefficient μ.
/// The normal is normalised on use (zero is rejected).
struct Contact {
  std::string link;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double friction = 0.5;
  std::string other_link;  ///< empty: the world
};

}  // namespace pathpace
