// The torque coefficients of eq. (12) at many samples: the SIMD variants of the fused sweep (abc_sweep.hpp),
// one per lane width, the run-time choice between them, and RobotModel::path_torque_coefficients{,_batch}.
//
// One file for the variants and their dispatch: each is path_torque_lanes<V> compiled with its own
// target("..."), its helpers forced inline (PATHPACE_LANE_INLINE). joint_transform, which each variant calls
// for joints outside sincos_lanes' reach, is defined here too so that those calls bind directly
// (cpp/CMakeLists.txt: -fno-semantic-interposition), not through the PLT of the Python module.
#include "robot/torque_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>

#include "base/validate.hpp"
#include "robot/abc_sweep.hpp"
#include "robot/bodies.hpp"
#include "robot/joint_transform.hpp"
#include "robot/sincos_lanes.hpp"

namespace pathpace {

namespace detail {

void joint_transform(const Body& b, double q, double* E, double* r) {
  const double* T = b.E_tree.data();
  if (b.type == RobotModel::JointType::Prismatic) {
    // E = E_tree; r = r_tree + E_tree^T (axis q).
    std::copy(T, T + 9, E);
    Eigen::Map<Eigen::Vector3d> origin(r);
    origin = b.r_tree + b.E_tree.transpose() * (b.axis * q);
    return;
  }
  // E = E_J E_tree with E_J = Rot(axis, q)^T; r = r_tree.
  std::copy(b.r_tree.data(), b.r_tree.data() + 3, r);
  const int unit = unit_axis(b);  // revolute here (prismatic returned above)
  if (unit < 0) {
    Eigen::Map<Eigen::Matrix3d> rotation(E);
    rotation.noalias() = Eigen::AngleAxisd(-q, b.axis).toRotationMatrix() * b.E_tree;
    return;
  }
  unit_axis_rotation<double>(b, unit, std::cos(q), std::sin(q), E);
}

}  // namespace detail

namespace {

using detail::abc_sweep;
using detail::AbcBody;
using detail::Body;
using detail::joint_transform;
using detail::RobotScratch;
using detail::sincos_lanes;
using detail::unit_axis;
using detail::unit_axis_rotation;

// The AbcBody array of a workspace's byte buffer (RobotScratch::abc), aligned for T, followed by `extra` more T.
template <typename T>
AbcBody<T>* abc_bodies(RobotScratch& ws, size_t nb, size_t extra = 0) {
  const size_t size = nb * sizeof(AbcBody<T>) + extra * sizeof(T);
  const size_t bytes = size + alignof(AbcBody<T>);
  if (ws.abc.size() < bytes) ws.abc.resize(bytes);
  void* p = ws.abc.data();
  size_t space = ws.abc.size();
  p = std::align(alignof(AbcBody<T>), size, p, space);
  return static_cast<AbcBody<T>*>(p);
}

#if defined(__GNUC__)
using Double2 = double __attribute__((vector_size(16)));  // two samples, one per SIMD lane (SSE2, NEON)
#if defined(__x86_64__) || defined(__i386__)
#define PATHPACE_WIDE_LANES 1
using Double4 = double __attribute__((vector_size(32)));  // AVX2
using Double8 = double __attribute__((vector_size(64)));  // AVX-512
#endif

// A constraint's row pair of eq. (15) at out's index `at` (see TorqueOutput): (a, b, τ_U - c) and (-a, -b, c - τ_L),
// with limit_or_inf's bounds (no limit: +inf - c and c + inf, an inactive row).
inline void store_row_pair(const detail::TorqueOutput& out, Eigen::Index at, double up, double lo, double a, double b,
                           double c) {
  out.a[at] = a;
  out.a[at + 1] = -a;
  out.b[at] = b;
  out.b[at + 1] = -b;
  out.c[at] = up - c;
  out.c[at + 1] = c - lo;
}

// Joint j's (τ_U, τ_L) for store_row_pair: an infinite limit as +inf and -inf.
inline std::pair<double, double> limit_or_inf(const detail::TorqueOutput& out, size_t j) {
  const double inf = std::numeric_limits<double>::infinity();
  return {std::isfinite(out.upper[j]) ? out.upper[j] : inf, std::isfinite(out.lower[j]) ? out.lower[j] : -inf};
}

// path_torque_coefficients_batch without mimic joints, W = sizeof(V) / 8 samples per sweep. q, dq, ddq
// are column-major (samples, bodies) with leading dimension `count`; a last group of fewer than W
// samples fills its spare lanes with its last sample and stores only its own.
template <typename V>
PATHPACE_LANE_INLINE void path_torque_lanes(const std::vector<Body>& bodies, const Eigen::Vector3d& gravity,
                                            RobotScratch& ws, Eigen::Index count, const double* q, const double* dq,
                                            const double* ddq, const detail::TorqueOutput& out) {
  constexpr Eigen::Index W = sizeof(V) / sizeof(double);
  const size_t nb = bodies.size();
  AbcBody<V>* S = abc_bodies<V>(ws, nb, 5 * nb);
  V* qd = reinterpret_cast<V*>(S + nb);
  V *qdd = qd + nb, *av = qdd + nb, *bv = av + nb, *cv = bv + nb;
  // Per body: the coordinate axis of a revolute joint whose angles all lie within sincos_lanes' range,
  // else -1 (joint_transform in each lane, with libm's sin and cos).
  std::vector<int> unit(nb);
  for (size_t i = 0; i < nb; ++i) {
    unit[i] = unit_axis(bodies[i]);
    if (unit[i] < 0) continue;
    const double* col = q + static_cast<Eigen::Index>(i) * count;
    bool in_range = true;
    for (Eigen::Index s = 0; s < count; ++s) in_range &= std::abs(col[s]) <= 1e5;  // false for NaN
    if (!in_range) unit[i] = -1;
  }
  for (Eigen::Index s = 0; s < count; s += W) {
    const Eigen::Index valid = std::min(W, count - s);
    const auto load = [&](const double* x, Eigen::Index j, V& y) {
      const double* col = x + j * count + s;
      if (valid == W) {
        std::memcpy(&y, col, sizeof(V));
      } else {
        for (Eigen::Index l = 0; l < W; ++l) y[l] = col[std::min(l, valid - 1)];
      }
    };
    for (size_t i = 0; i < nb; ++i) {
      const Body& bd = bodies[i];
      const Eigen::Index j = static_cast<Eigen::Index>(i);
      load(dq, j, qd[i]);
      load(ddq, j, qdd[i]);
      V qv;
      load(q, j, qv);
      AbcBody<V>& B = S[i];
      if (unit[i] >= 0) {
        V sq, cq;
        sincos_lanes(qv, sq, cq);
        unit_axis_rotation<V>(bd, unit[i], cq, sq, B.E);
      } else {
        for (Eigen::Index l = 0; l < W; ++l) {
          double E[9], r[3];
          joint_transform(bd, qv[l], E, r);
          for (int k = 0; k < 9; ++k) B.E[k][l] = E[k];
          for (int k = 0; k < 3; ++k) B.r[k][l] = r[k];
        }
      }
    }
    abc_sweep<V>(bodies, S, qd, qdd, gravity, av, bv, cv);
    const Eigen::Index ss = out.sample_stride;
    for (size_t i = 0; i < nb; ++i) {
      const Eigen::Index at = static_cast<Eigen::Index>(i) * out.joint_stride + s * ss;
      if (out.upper) {  // a constraint's row pair, see TorqueOutput
        const auto [up, lo] = limit_or_inf(out, i);
        for (Eigen::Index l = 0; l < valid; ++l) store_row_pair(out, at + l * ss, up, lo, av[i][l], bv[i][l], cv[i][l]);
      } else if (valid == W && ss == 1) {
        std::memcpy(out.a + at, &av[i], sizeof(V));
        std::memcpy(out.b + at, &bv[i], sizeof(V));
        std::memcpy(out.c + at, &cv[i], sizeof(V));
      } else {
        for (Eigen::Index l = 0; l < valid; ++l) {
          out.a[at + l * ss] = av[i][l];
          out.b[at + l * ss] = bv[i][l];
          out.c[at + l * ss] = cv[i][l];
        }
      }
    }
  }
}

void path_torque_lanes2(const std::vector<Body>& bodies, const Eigen::Vector3d& gravity, RobotScratch& ws,
                        Eigen::Index count, const double* q, const double* dq, const double* ddq,
                        const detail::TorqueOutput& out) {
  path_torque_lanes<Double2>(bodies, gravity, ws, count, q, dq, ddq, out);
}
#if defined(PATHPACE_WIDE_LANES)
// The same code with the wider registers of newer x86-64 CPUs, chosen at run time (the library itself
// is built for the x86-64 baseline, SSE2). FMA contracts the products and sums: the results differ from
// the SSE2 variant's by rounding.
__attribute__((target("avx2,fma"))) void path_torque_lanes4(const std::vector<Body>& bodies,
                                                             const Eigen::Vector3d& gravity, RobotScratch& ws,
                                                             Eigen::Index count, const double* q, const double* dq,
                                                             const double* ddq, const detail::TorqueOutput& out) {
  path_torque_lanes<Double4>(bodies, gravity, ws, count, q, dq, ddq, out);
}
__attribute__((target("avx512f,avx512dq,avx2,fma"))) void path_torque_lanes8(
    const std::vector<Body>& bodies, const Eigen::Vector3d& gravity, RobotScratch& ws, Eigen::Index count,
    const double* q, const double* dq, const double* ddq, const detail::TorqueOutput& out) {
  path_torque_lanes<Double8>(bodies, gravity, ws, count, q, dq, ddq, out);
}
#endif
#endif

}  // namespace

namespace detail {

int torque_lanes_supported() {
#if defined(PATHPACE_WIDE_LANES)
  static const int widest = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") ? 8
                            : __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? 4
                                                                                             : 2;
  return widest;
#elif defined(__GNUC__)
  return 2;
#else
  return 1;
#endif
}

int default_torque_lanes() {
  // Read at every call (once per constraint's rows, not per sample), so that a test can switch it.
  const char* forced = std::getenv("PATHPACE_TORQUE_LANES");
  if (!forced || !*forced) return torque_lanes_supported();
  char* end = nullptr;
  const long lanes = std::strtol(forced, &end, 10);
  if (*end != '\0' || lanes < 1 || lanes > torque_lanes_supported() || (lanes & (lanes - 1)) != 0)
    fail(std::string("environment variable PATHPACE_TORQUE_LANES = '") + forced + "' must be a power of 2 <= " +
         std::to_string(torque_lanes_supported()) + " (the widest this CPU runs), or unset");
  return static_cast<int>(lanes);
}

void check_sample_shapes(Eigen::Index n, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq) {
  const Eigen::Index count = q.rows();
  if (q.cols() != n || dq.cols() != n || ddq.cols() != n || dq.rows() != count || ddq.rows() != count)
    fail("q, dq, ddq must all have shape (samples, " + std::to_string(n) + ")");
}

void path_torque_coefficients_into(const RobotModel& robot, RobotWorkspace& ws, const Eigen::MatrixXd& q,
                                   const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, const TorqueOutput& out,
                                   int lanes) {
  const Eigen::Index n = robot.nq(), count = q.rows();
  check_sample_shapes(n, q, dq, ddq);
  if (lanes == 0) lanes = default_torque_lanes();
  if (lanes < 1 || lanes > torque_lanes_supported() || (lanes & (lanes - 1)) != 0)
    fail("lanes = " + std::to_string(lanes) + " must be a power of 2 <= " + std::to_string(torque_lanes_supported()));
  const std::vector<Body>& bodies = RobotInternals::bodies(robot);
  RobotScratch& scratch = RobotInternals::scratch(ws, robot);
  if (robot.mimic_joints().empty()) {
    switch (lanes) {
#if defined(PATHPACE_WIDE_LANES)
      case 8:
        path_torque_lanes8(bodies, robot.gravity(), scratch, count, q.data(), dq.data(), ddq.data(), out);
        return;
      case 4:
        path_torque_lanes4(bodies, robot.gravity(), scratch, count, q.data(), dq.data(), ddq.data(), out);
        return;
#endif
#if defined(__GNUC__)
      case 2:
        path_torque_lanes2(bodies, robot.gravity(), scratch, count, q.data(), dq.data(), ddq.data(), out);
        return;
#endif
      default:
        break;
    }
  }
  // One sample at a time, or a robot with mimic joints (the batch maps them onto its bodies' model).
  auto store = [&](Eigen::Index s, const auto& a, const auto& b, const auto& c) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::Index at = s * out.sample_stride + j * out.joint_stride;
      if (out.upper) {
        const auto [up, lo] = limit_or_inf(out, static_cast<size_t>(j));
        store_row_pair(out, at, up, lo, a(j), b(j), c(j));
      } else {
        out.a[at] = a(j);
        out.b[at] = b(j);
        out.c[at] = c(j);
      }
    }
  };
  if (robot.mimic_joints().empty()) {
    // The samples' rows copied into vectors held across the loop (a row of a column-major matrix is not
    // contiguous: passed as it is, each would be copied into a new vector per sample).
    Eigen::VectorXd as(n), bs(n), cs(n), qs(n), dqs(n), ddqs(n);
    for (Eigen::Index s = 0; s < count; ++s) {
      qs = q.row(s).transpose();
      dqs = dq.row(s).transpose();
      ddqs = ddq.row(s).transpose();
      robot.path_torque_coefficients(ws, qs, dqs, ddqs, as, bs, cs);
      store(s, as, bs, cs);
    }
  } else {
    Eigen::MatrixXd A, B, C;
    robot.path_torque_coefficients_batch(ws, q, dq, ddq, A, B, C);
    for (Eigen::Index s = 0; s < count; ++s) store(s, A.row(s), B.row(s), C.row(s));
  }
}

void path_torque_coefficients_lanes(const RobotModel& robot, RobotWorkspace& ws, const Eigen::MatrixXd& q,
                                    const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, Eigen::MatrixXd& a,
                                    Eigen::MatrixXd& b, Eigen::MatrixXd& c, int lanes) {
  check_sample_shapes(robot.nq(), q, dq, ddq);
  a.resize(q.rows(), robot.nq());
  b.resize(q.rows(), robot.nq());
  c.resize(q.rows(), robot.nq());
  path_torque_coefficients_into(robot, ws, q, dq, ddq, TorqueOutput{a.data(), b.data(), c.data(), 1, q.rows()}, lanes);
}

}  // namespace detail

void RobotModel::path_torque_coefficients(RobotWorkspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                                          const Eigen::Ref<const Eigen::VectorXd>& dq,
                                          const Eigen::Ref<const Eigen::VectorXd>& ddq, Eigen::Ref<Eigen::VectorXd> a,
                                          Eigen::Ref<Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> c) const {
  // eq. (12): τ = M (p'' ṡ² + p' s̈) + C(q, p' ṡ) p' ṡ + g, and C is quadratic in the velocity, so
  // a = M p'' + C(q, p') p' = RNEA(q, p', p'') without gravity, b = M p' = RNEA(q, 0, p') without
  // gravity, c = g(q): three RNEA channels in one sweep (abc_sweep).
  if (mimic_) {
    const detail::MimicMap& mm = *mimic_;
    const Eigen::Index nbodies = static_cast<Eigen::Index>(tree_->bodies.size());
    Eigen::VectorXd ab(nbodies), bb(nbodies), cb(nbodies);
    mm.bodies_model->path_torque_coefficients(ws, mm.E * q + mm.o, mm.E * dq, mm.E * ddq, ab, bb, cb);
    a.noalias() = mm.E.transpose() * ab;
    b.noalias() = mm.E.transpose() * bb;
    c.noalias() = mm.E.transpose() * cb;
    return;
  }
  const std::vector<detail::Body>& bodies = tree_->bodies;
  const size_t nb = bodies.size();
  AbcBody<double>* S = abc_bodies<double>(detail::RobotInternals::scratch(ws, *this), nb);
  for (size_t i = 0; i < nb; ++i) detail::joint_transform(bodies[i], q[static_cast<Eigen::Index>(i)], S[i].E, S[i].r);
  detail::abc_sweep<double>(bodies, S, dq.data(), ddq.data(), gravity_, a.data(), b.data(), c.data());
}

void RobotModel::path_torque_coefficients_batch(RobotWorkspace& ws, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                                const Eigen::MatrixXd& ddq, Eigen::MatrixXd& a, Eigen::MatrixXd& b,
                                                Eigen::MatrixXd& c) const {
  if (mimic_) {
    detail::check_sample_shapes(nq(), q, dq, ddq);  // before the products below (else _into checks them)
    const detail::MimicMap& mm = *mimic_;
    const Eigen::MatrixXd qb = (q * mm.E.transpose()).rowwise() + mm.o.transpose();
    const Eigen::MatrixXd dqb = dq * mm.E.transpose(), ddqb = ddq * mm.E.transpose();
    Eigen::MatrixXd ab, bb, cb;
    mm.bodies_model->path_torque_coefficients_batch(ws, qb, dqb, ddqb, ab, bb, cb);
    a.noalias() = ab * mm.E;
    b.noalias() = bb * mm.E;
    c.noalias() = cb * mm.E;
    return;
  }
  // As many samples per sweep as the CPU has SIMD lanes (8 with AVX-512, 4 with AVX2, 2 with SSE2).
  detail::path_torque_coefficients_lanes(*this, ws, q, dq, ddq, a, b, c);
}

}  // namespace pathpace
