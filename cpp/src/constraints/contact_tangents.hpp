#pragma once
// The tangent directions (t1, t2) of a contact normal n: the cone generators of the projection's LP and the
// friction facets of the centred force distribution are built on them, so both are the same pyramid.

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pathpace::detail {

inline void contact_tangents(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  const Eigen::Vector3d e = std::abs(n.x()) > 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  t1 = n.cross(e).normalized();
  t2 = n.cross(t1);
}

}  // namespace pathpace::detail
