#pragma once
// Internal: sin and cos of every SIMD lane at once, for the joint rotations of torque_lanes.cpp.

#include "robot/joint_transform.hpp"

namespace pathpace::detail {

// sin and cos of every lane at once, to within 2 ulp of libm's: the reduction by π/2 in three parts
// (Cody-Waite, fdlibm's constants; exact for |x| <= 1e5, which the caller ensures) and fdlibm's kernels on
// [-π/4, π/4]. Ours because libm's sincos takes one double: called per lane, joint and sample, it cost as
// much as a good part of the sweep. The quadrant picks and signs the kernels by products with 0, 1 and ±1
// (exact), not by lane comparisons: GCC does those one lane at a time with AVX-512.
template <typename V>
PATHPACE_LANE_INLINE void sincos_lanes(const V& x, V& s, V& c) {
  const double magic = 6755399441055744.0;  // 1.5 · 2^52: y + magic - magic rounds y to an integer
  const V k = (x * 0.63661977236758134308 + magic) - magic;  // nearest multiple of π/2
  V r = x - k * 1.57079632673412561417e+00;
  r = r - k * 6.07710050630396597660e-11;
  r = r - k * 2.02226624879595063154e-21;
  const V z = r * r;
  const V sp =
      r + r * z *
              (-1.66666666666666324348e-01 +
               z * (8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 +
                         z * (2.75573137070700676789e-06 + z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
  const V cp =
      1.0 - 0.5 * z +
      z * z *
          (4.16666666666666019037e-02 +
           z * (-1.38888888888741095749e-03 +
                z * (2.48015872894767294178e-05 +
                     z * (-2.75573143513906633035e-07 + z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  // The quadrant q = k mod 4 in 0..3 = 2 hi + odd: sin x = ±(sp or cp), cos x = ±(cp or sp); every
  // step is exact in doubles (|k| < 2^50).
  const V q = k - 4.0 * ((k * 0.25 - 0.375 + magic) - magic);
  const V hi = (q * 0.5 - 0.25 + magic) - magic;
  const V odd = q - 2.0 * hi;
  const V even = 1.0 - odd;
  const V sin_sign = 1.0 - 2.0 * hi;
  const V cos_sign = 1.0 - 2.0 * (hi + odd - 2.0 * hi * odd);  // + in quadrants 0 and 3
  s = sin_sign * (sp * even + cp * odd);
  c = cos_sign * (cp * even + sp * odd);
}

}  // namespace pathpace::detail
