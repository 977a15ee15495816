#pragma once
// Internal: one joint's transform ^iX_λ = X_J(q) X_tree, for one sample (joint_transform) or for a
// vector of samples, one per SIMD lane (unit_axis_rotation), shared by rnea.cpp and torque_lanes.cpp.

#include "robot/bodies.hpp"

// Every helper of the torque sweep is forced inline, so that it is compiled with the instruction set of
// the lane-width variant that calls it (torque_lanes.cpp: a function of target("avx2,fma") gets AVX2
// code for its whole body). Only torque_lanes.cpp calls them with vector types.
#if defined(__GNUC__)
#define PATHPACE_LANE_INLINE inline __attribute__((always_inline))
#else
#define PATHPACE_LANE_INLINE inline
#endif

namespace pathpace::detail {

template <typename T>
PATHPACE_LANE_INLINE void splat(T& y, double x) {  // every lane x (not 0 + x, which would turn -0 into +0)
  for (size_t l = 0; l < sizeof(T) / sizeof(double); ++l) y[l] = x;
}
PATHPACE_LANE_INLINE void splat(double& y, double x) { y = x; }

// The coordinate axis a revolute joint turns about (most URDF joints), else -1. (The test abc_sweep makes:
// an axis with x = 1 after normalisation but a 1e-9 component left is not e_x for either.)
inline int unit_axis(const Body& b) { return b.type == RobotModel::JointType::Revolute ? b.axis_index : -1; }

// E = E_J E_tree for a rotation by q about coordinate axis `unit`, given cos q and sin q: E_J mixes two
// rows of E_tree only: e_i1 -> c e_i1 + s e_i2, e_i2 -> -s e_i1 + c e_i2. T is double (one sample) or a
// vector of lanes (path_torque_lanes: one sample per lane).
template <typename T>
PATHPACE_LANE_INLINE void unit_axis_rotation(const Body& b, int unit, const T& cq, const T& sq, T* E) {
  const double* Et = b.E_tree.data();
  const int i1 = (unit + 1) % 3, i2 = (unit + 2) % 3;
  for (int col = 0; col < 3; ++col) {
    const double t1 = Et[3 * col + i1], t2 = Et[3 * col + i2];
    splat(E[3 * col + unit], Et[3 * col + unit]);
    E[3 * col + i1] = cq * t1 + sq * t2;
    E[3 * col + i2] = cq * t2 - sq * t1;
  }
}

/// ^iX_λ of one body as its rotation E (column-major, 9 values) and the origin r of the joint frame in
/// parent coordinates. Defined in torque_lanes.cpp, beside its hottest callers.
void joint_transform(const Body& b, double q, double* E, double* r);

}  // namespace pathpace::detail
