#pragma once
/// @file contact.hpp
/// A frictional point contact between a robot link and the world (sec. III.b).

#include <string>

#include <Eigen/Core>

namespace pathpace {

/// A point fixed in `link` (coordinates in the link frame) touching the world, with the contact normal
/// in world coordinates pointing into the robot (the direction of the force the world can push with)
/// and Coulomb friction coefficient `friction`. The normal is normalised on use (zero is rejected).
struct Contact {
  std::string link;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double friction = 0.5;
};

}  // namespace pathpace
