#pragma once
// Internal: the fused sweep of eq. (12) that RobotModel::path_torque_coefficients and the SIMD variants of
// torque_lanes.cpp run, written once for a scalar T (double: one sample) or a GCC vector of W doubles (W
// samples, one per SIMD lane). Included by torque_lanes.cpp only: every function here is forced inline
// into the lane-width variant that calls it (see PATHPACE_LANE_INLINE).

#include <vector>

#include "robot/bodies.hpp"
#include "robot/joint_transform.hpp"

namespace pathpace::detail {

// One body of the sweep, for T = double or a vector of lanes. Plain arrays, E column-major as Eigen
// stores it: the compiler unrolls every 3x3 kernel completely. Aligned to the size of T: outside AVX code
// (the library's baseline) GCC gives a 32- or 64-byte vector type only 16-byte alignment, while the AVX
// code of the variants moves whole vectors with aligned loads and stores. T members only, m last: each
// lies on a multiple of sizeof(T).
template <typename T>
struct alignas(sizeof(T)) AbcBody {
  T aw[3], al[3];  // channel a (q̇ = p', q̈ = p''): acceleration (ω̇, v̇)
  T v[6];          // its velocity (ω then linear), which is channel b's acceleration (q̇ = 0, q̈ = p')
  T fw[6], fl[6];  // forces (moment, linear) of channel a at [0, 3), b at [3, 6)
  T g[3];          // channel c: the base's upward acceleration -gravity in body coordinates
  T h[3];          // channel c: first moment of mass of the subtree about the body origin
  T E[9], r[3];    // ^iX_λ's rotation and origin (r read for prismatic joints only: see transform_from_parent)
  double m;        // channel c: mass of the subtree
};

template <typename T, typename M>
PATHPACE_LANE_INLINE void mul_E(const M* E, const T* x, T* y) {  // y = E x
  y[0] = E[0] * x[0] + E[3] * x[1] + E[6] * x[2];
  y[1] = E[1] * x[0] + E[4] * x[1] + E[7] * x[2];
  y[2] = E[2] * x[0] + E[5] * x[1] + E[8] * x[2];
}
template <typename T>
PATHPACE_LANE_INLINE void mul_Et(const T* E, const T* x, T* y) {  // y = E^T x
  y[0] = E[0] * x[0] + E[1] * x[1] + E[2] * x[2];
  y[1] = E[3] * x[0] + E[4] * x[1] + E[5] * x[2];
  y[2] = E[6] * x[0] + E[7] * x[1] + E[8] * x[2];
}
template <typename A, typename B, typename T>
PATHPACE_LANE_INLINE void cross(const A* a, const B* b, T* y) {  // y = a × b
  y[0] = a[1] * b[2] - a[2] * b[1];
  y[1] = a[2] * b[0] - a[0] * b[2];
  y[2] = a[0] * b[1] - a[1] * b[0];
}
template <typename A, typename B, typename T>
PATHPACE_LANE_INLINE void add_cross(const A* a, const B* b, T* y) {  // y += a × b
  y[0] += a[1] * b[2] - a[2] * b[1];
  y[1] += a[2] * b[0] - a[0] * b[2];
  y[2] += a[0] * b[1] - a[1] * b[0];
}
template <typename A, typename B, typename T>
PATHPACE_LANE_INLINE void sub_cross(const A* a, const B* b, T* y) {  // y -= a × b
  y[0] -= a[1] * b[2] - a[2] * b[1];
  y[1] -= a[2] * b[0] - a[0] * b[2];
  y[2] -= a[0] * b[1] - a[1] * b[0];
}
template <typename T>
PATHPACE_LANE_INLINE void mul_sym(const double* I, const T* x, T* y) {  // y = Ī x, Ī the 6x6's top-left block
  y[0] = I[0] * x[0] + I[6] * x[1] + I[12] * x[2];
  y[1] = I[1] * x[0] + I[7] * x[1] + I[13] * x[2];
  y[2] = I[2] * x[0] + I[8] * x[1] + I[14] * x[2];
}
template <typename T>
PATHPACE_LANE_INLINE void dot_axis(const double* ax, const T* x, T& y) {  // y = ax · x
  y = ax[0] * x[0] + ax[1] * x[1] + ax[2] * x[2];
}
// abc_sweep's joint terms for the axis e_U (URDF joints mostly have one): vJ = q̇ e_U, and x × vJ =
// q̇ (x[U+2], -x[U+1]) at (U+1, U+2) mod 3, without the products with the axis' zeros. U a constant,
// so that every array stays in registers.
template <int U, typename T>
PATHPACE_LANE_INLINE void joint_motion_on_axis(bool revolute, const T& qd, const T& qdd, T* aw, T* al, T* v) {
  constexpr int i1 = (U + 1) % 3, i2 = (U + 2) % 3;
  if (revolute) {
    aw[U] += qdd;
    v[U] += qd;
    aw[i1] += v[i2] * qd;  // ω × vJ
    aw[i2] -= v[i1] * qd;
    al[i1] += v[3 + i2] * qd;  // v × vJ
    al[i2] -= v[3 + i1] * qd;
  } else {
    al[U] += qdd;
    v[3 + U] += qd;
    al[i1] += v[i2] * qd;  // ω × vJ
    al[i2] -= v[i1] * qd;
  }
}

// abc_sweep's projections on the axis e_U: a component, and one component of the gravity moment.
template <int U, typename T>
PATHPACE_LANE_INLINE void project_on_axis(bool revolute, const AbcBody<T>& B, T& a, T& b, T& c) {
  constexpr int i1 = (U + 1) % 3, i2 = (U + 2) % 3;
  if (revolute) {
    a = B.fw[U];
    b = B.fw[3 + U];
    c = B.h[i1] * B.g[i2] - B.h[i2] * B.g[i1];
  } else {
    a = B.fl[U];
    b = B.fl[3 + U];
    c = B.m * B.g[U];
  }
}

// Body i's channels from its parent's by ^iX_λ: ω' = E ω, v' = E (v - r × ω). r is the joint's
// origin: the same in every lane for a revolute joint (r_tree, so a constant operand), else B.r.
template <typename R, typename T>
PATHPACE_LANE_INLINE void transform_from_parent(const R* r, const AbcBody<T>& P, AbcBody<T>& B) {
  const T* E = B.E;
  mul_E(E, P.aw, B.aw);
  T t[3] = {P.al[0], P.al[1], P.al[2]};
  sub_cross(r, P.aw, t);
  mul_E(E, t, B.al);
  mul_E(E, P.v, B.v);
  T vt[3] = {P.v[3], P.v[4], P.v[5]};
  sub_cross(r, P.v, vt);
  mul_E(E, vt, B.v + 3);
  mul_E(E, P.g, B.g);
}

// f_λ += ^iX_λ^T f: n' = E^T n + r × (E^T f), f' = E^T f, for channels a and b; the first moment of
// mass moves as a point mass. r as in transform_from_parent.
template <typename R, typename T>
PATHPACE_LANE_INLINE void add_to_parent(const R* r, const AbcBody<T>& B, AbcBody<T>& P) {
  for (int ch = 0; ch < 2; ++ch) {
    T fl[3], fw[3];
    mul_Et(B.E, B.fl + 3 * ch, fl);
    mul_Et(B.E, B.fw + 3 * ch, fw);
    for (int k = 0; k < 3; ++k) {
      P.fw[3 * ch + k] += fw[k];
      P.fl[3 * ch + k] += fl[k];
    }
    add_cross(r, fl, P.fw + 3 * ch);
  }
  T hp[3];
  mul_Et(B.E, B.h, hp);
  for (int k = 0; k < 3; ++k) P.h[k] += hp[k] + B.m * r[k];
  P.m += B.m;
}

// eq. (12) by one sweep carrying three RNEA channels: a with q̇ = p', q̈ = p'' (velocity products
// included), b with q̇ = 0, q̈ = p', c with gravity only. S[i].E and S[i].r must hold body i's
// transform. Channel b's acceleration obeys the recursion of channel a's velocity (a_i = ^iX_λ a_λ +
// S_i p'_i from zero at the root), so it is that velocity, and its force I a is the I v that a's velocity
// product needs. Channel c's acceleration is the base's -gravity rotated into each body (no angular
// part), the same vector for every body of a subtree, so its forces need no backward transform of their
// own: the torque about joint i is the subtree's first moment of mass × that acceleration. The spatial
// inertia is applied through its parts (m, h = m c, Ī about the body origin): I (ω, v) = (Ī ω + h × v,
// m v - h × ω).
template <typename T>
PATHPACE_LANE_INLINE void abc_sweep(const std::vector<Body>& bodies, AbcBody<T>* S, const T* dq,
                                    const T* ddq, const Eigen::Vector3d& gravity, T* a, T* b, T* c) {
  const size_t nb = bodies.size();
  const T zero = T{} * 0.0;
  const T root_g[3] = {zero - gravity[0], zero - gravity[1], zero - gravity[2]};  // an upward base acceleration
  for (size_t i = 0; i < nb; ++i) {
    const Body& bd = bodies[i];
    AbcBody<T>& B = S[i];
    const T* E = B.E;
    T* v = B.v;
    if (bd.parent >= 0) {
      const AbcBody<T>& P = S[static_cast<size_t>(bd.parent)];
      if (bd.type == RobotModel::JointType::Revolute) transform_from_parent(bd.r_tree.data(), P, B);
      else transform_from_parent(B.r, P, B);
    } else {
      for (int k = 0; k < 3; ++k) B.aw[k] = B.al[k] = zero;
      for (int k = 0; k < 6; ++k) v[k] = zero;
      mul_E(E, root_g, B.g);
    }
    const T qd = dq[i], qdd = ddq[i];
    const double ax[3] = {bd.axis[0], bd.axis[1], bd.axis[2]};
    const bool revolute = bd.type == RobotModel::JointType::Revolute;
    const int u = bd.axis_index;
    if (u == 0) {
      joint_motion_on_axis<0>(revolute, qd, qdd, B.aw, B.al, v);
    } else if (u == 1) {
      joint_motion_on_axis<1>(revolute, qd, qdd, B.aw, B.al, v);
    } else if (u == 2) {
      joint_motion_on_axis<2>(revolute, qd, qdd, B.aw, B.al, v);
    } else if (revolute) {
      const T vj[3] = {ax[0] * qd, ax[1] * qd, ax[2] * qd};
      for (int k = 0; k < 3; ++k) {
        B.aw[k] += ax[k] * qdd;
        v[k] += vj[k];
      }
      add_cross(v, vj, B.aw);      // ω × vJ
      add_cross(v + 3, vj, B.al);  // v × vJ (angular joint motion)
    } else {
      const T vj[3] = {ax[0] * qd, ax[1] * qd, ax[2] * qd};
      for (int k = 0; k < 3; ++k) {
        B.al[k] += ax[k] * qdd;
        v[3 + k] += vj[k];
      }
      add_cross(v, vj, B.al);  // ω × vJ (linear joint motion)
    }
    const double* I6 = bd.inertia.data();
    const double m = I6[21];
    const double h[3] = {I6[26], I6[30], I6[19]};  // (I(2,4), I(0,5), I(1,3)) of m [c]x
    // Channel b: f = I v.
    T* Iw = B.fw + 3;
    T* Il = B.fl + 3;
    mul_sym(I6, v, Iw);
    add_cross(h, v + 3, Iw);
    T t[3];
    cross(h, v, t);
    for (int k = 0; k < 3; ++k) Il[k] = m * v[3 + k] - t[k];
    // Channel a: f = I a + v ×* I v.
    mul_sym(I6, B.aw, B.fw);
    cross(h, B.aw, t);
    for (int k = 0; k < 3; ++k) B.fl[k] = m * B.al[k] - t[k];
    add_cross(h, B.al, B.fw);
    add_cross(v, Iw, B.fw);
    add_cross(v + 3, Il, B.fw);
    add_cross(v, Il, B.fl);
    // Channel c: the body's own mass and moment; the children add theirs below.
    for (int k = 0; k < 3; ++k) splat(B.h[k], h[k]);
    B.m = m;
  }
  for (size_t i = nb; i-- > 0;) {
    const Body& bd = bodies[i];
    AbcBody<T>& B = S[i];
    const double* ax = bd.axis.data();
    const int u = bd.axis_index;
    if (u == 0) {
      project_on_axis<0>(bd.type == RobotModel::JointType::Revolute, B, a[i], b[i], c[i]);
    } else if (u == 1) {
      project_on_axis<1>(bd.type == RobotModel::JointType::Revolute, B, a[i], b[i], c[i]);
    } else if (u == 2) {
      project_on_axis<2>(bd.type == RobotModel::JointType::Revolute, B, a[i], b[i], c[i]);
    } else if (bd.type == RobotModel::JointType::Revolute) {
      dot_axis(ax, B.fw, a[i]);
      dot_axis(ax, B.fw + 3, b[i]);
      T n[3];
      cross(B.h, B.g, n);
      dot_axis(ax, n, c[i]);
    } else {
      dot_axis(ax, B.fl, a[i]);
      dot_axis(ax, B.fl + 3, b[i]);
      dot_axis(ax, B.g, c[i]);
      c[i] *= B.m;
    }
    if (bd.parent >= 0) {
      // f_λ += ^iX_λ^T f: n' = E^T n + r × (E^T f), f' = E^T f; the first moment moves as a point mass.
      AbcBody<T>& P = S[static_cast<size_t>(bd.parent)];
      if (bd.type == RobotModel::JointType::Revolute) add_to_parent(bd.r_tree.data(), B, P);
      else add_to_parent(B.r, B, P);
    }
  }
}

}  // namespace pathpace::detail
