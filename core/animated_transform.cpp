#include "core/animated_transform.h"

#include <cmath>

#include "core/error.h"

namespace kiln {
namespace {

using Mat3d = std::array<std::array<double, 3>, 3>;
using Quat = std::array<double, 4>;  // x y z w

// The polar iteration stops when no entry moves by more than this.
constexpr double kPolarTolerance = 1e-13;
constexpr int kPolarMaxIterations = 100;
// Below this quaternion angle slerp is replaced by the normalised linear blend (sin x / x is then 1 to double
// precision).
constexpr double kSlerpLinearBelow = 1e-6;
// Motion bounds: each sub-interval may turn the object by at most this angle (radians); the box of a sub-interval
// is padded by the distance a point can travel in half of it, so finer steps give tighter boxes.
constexpr double kBoundsMaxTurn = 3.14159265358979323846 / 32.0;
// Outward padding of the bounds, relative to their magnitude, for the rounding of the double results to float.
constexpr double kBoundsRoundingPad = 1e-6;

double det3(const Mat3d& a) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

bool inverse3(const Mat3d& a, Mat3d& out) {
  const double d = det3(a);
  if (!(std::abs(d) > 0.0) || !std::isfinite(d)) return false;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      // Cofactor of (c, r): the adjugate is the transposed cofactor matrix.
      const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
      out[size_t(r)][size_t(c)] = (a[size_t(r0)][size_t(c0)] * a[size_t(r1)][size_t(c1)] -
                                   a[size_t(r0)][size_t(c1)] * a[size_t(r1)][size_t(c0)]) /
                                  d;
    }
  return true;
}

Mat3d mul3(const Mat3d& a, const Mat3d& b) {
  Mat3d r{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  return r;
}

Mat3d transpose3(const Mat3d& a) {
  Mat3d r{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) r[i][j] = a[j][i];
  return r;
}

// Unit quaternion of a proper rotation matrix (the largest of w, x, y, z is computed first, so it never divides by
// a small number).
Quat quaternion_of(const Mat3d& m) {
  const double trace = m[0][0] + m[1][1] + m[2][2];
  Quat q{};
  if (trace > 0.0) {
    const double s = 2.0 * std::sqrt(trace + 1.0);
    q = {(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s};
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
    q = {0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s};
  } else if (m[1][1] > m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
    q = {(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
    q = {(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s};
  }
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= n;
  return q;
}

Mat3d rotation_of(const Quat& q) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  return Mat3d{{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
}

double qdot(const Quat& a, const Quat& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]; }

// Rotation (proper) and stretch of the linear part: L = R S with S symmetric (polar decomposition by the averaged
// inverse-transpose iteration, R <- (R + R^-T) / 2, which converges quadratically to the orthogonal factor).
void polar(Mat3d linear, Mat3d& rotation, Mat3d& stretch, bool mirrored) {
  if (mirrored)
    for (auto& row : linear)
      for (double& x : row) x = -x;
  Mat3d r = linear;
  for (int it = 0; it < kPolarMaxIterations; ++it) {
    Mat3d inv{};
    if (!inverse3(transpose3(r), inv)) throw Error("the transformation is singular (it has no rotation part)");
    double change = 0.0;
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const double next = 0.5 * (r[i][j] + inv[i][j]);
        change = std::max(change, std::abs(next - r[i][j]));
        r[i][j] = next;
      }
    if (change <= kPolarTolerance) break;
  }
  rotation = r;
  stretch = mul3(transpose3(r), linear);
  if (mirrored)
    for (auto& row : stretch)
      for (double& x : row) x = -x;
}

double length3(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

std::array<double, 3> apply3(const Mat3d& m, const std::array<double, 3>& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

std::array<double, 3> corner(const Bounds3f& b, int i) {
  return {(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z};
}

}  // namespace

AnimatedTransform::AnimatedTransform(const Transform& start, float start_time, const Transform& end, float end_time)
    : start_(start), end_(end), t0_(start_time), t1_(end_time), animated_(start.matrix() != end.matrix()) {
  if (!animated_) return;
  if (!(t1_ > t0_)) throw Error("the transform times must increase (end after start)");
  const bool mirrored = start.swaps_handedness();
  if (end.swaps_handedness() != mirrored)
    throw Error("one keyframe mirrors and the other does not: no rotation turns one into the other");
  for (size_t k = 0; k < 2; ++k) {
    const Mat4& m = (k == 0 ? start : end).matrix();
    Mat3d linear{};
    for (size_t i = 0; i < 3; ++i) {
      key_[k].translation[i] = m.m[i][3];
      for (size_t j = 0; j < 3; ++j) linear[i][j] = m.m[i][j];
    }
    Mat3d rotation{};
    polar(linear, rotation, key_[k].stretch, mirrored);
    key_[k].rotation = quaternion_of(rotation);
  }
  // q and -q are the same rotation: take the one on the shorter arc from the start.
  if (qdot(key_[0].rotation, key_[1].rotation) < 0.0)
    for (double& c : key_[1].rotation) c = -c;
  half_angle_ = std::acos(std::clamp(qdot(key_[0].rotation, key_[1].rotation), -1.0, 1.0));
}

double AnimatedTransform::fraction(float time) const {
  if (!(time > t0_)) return 0.0;
  if (!(time < t1_)) return 1.0;
  return (double(time) - t0_) / (double(t1_) - t0_);
}

Transform AnimatedTransform::at(float time) const {
  if (!animated_ || !(time > t0_)) return start_;
  if (!(time < t1_)) return end_;
  return at_fraction(fraction(time));
}

Transform AnimatedTransform::at_fraction(double s) const {
  const Keyframe &a = key_[0], &b = key_[1];
  // Rotation: slerp along the great arc (constant angular speed), or the normalised blend for tiny angles.
  Quat q{};
  double wa = 1.0 - s, wb = s;
  if (half_angle_ > kSlerpLinearBelow) {
    const double sin_total = std::sin(half_angle_);
    wa = std::sin((1.0 - s) * half_angle_) / sin_total;
    wb = std::sin(s * half_angle_) / sin_total;
  }
  for (size_t i = 0; i < 4; ++i) q[i] = wa * a.rotation[i] + wb * b.rotation[i];
  const double qn = std::sqrt(qdot(q, q));
  for (double& c : q) c /= qn;
  Mat3d stretch{};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) stretch[i][j] = (1.0 - s) * a.stretch[i][j] + s * b.stretch[i][j];
  const Mat3d rotation = rotation_of(q);
  const Mat3d linear = mul3(rotation, stretch);
  Mat3d stretch_inv{};
  if (!inverse3(stretch, stretch_inv)) return s < 0.5 ? start_ : end_;  // a stretch passing through zero volume
  const Mat3d linear_inv = mul3(stretch_inv, transpose3(rotation));
  std::array<double, 3> t{};
  for (size_t i = 0; i < 3; ++i) t[i] = (1.0 - s) * a.translation[i] + s * b.translation[i];
  const std::array<double, 3> t_inv = apply3(linear_inv, t);
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = 0; j < 3; ++j) {
      m.m[i][j] = float(linear[i][j]);
      inv.m[i][j] = float(linear_inv[i][j]);
    }
    m.m[i][3] = float(t[i]);
    inv.m[i][3] = float(-t_inv[i]);
  }
  return Transform(m, inv);
}

Bounds3f AnimatedTransform::motion_bounds(const Bounds3f& b, float t0, float t1) const {
  if (b.empty()) return b;
  const double sa = fraction(std::min(t0, t1)), sb = fraction(std::max(t0, t1));
  if (!animated_ || sa == sb) return at(std::min(t0, t1)).bounds(b);
  Bounds3f out;
  if (half_angle_ == 0.0) {
    // No rotation: every point moves affinely in s, so the boxes at the ends hold the whole path.
    out.extend(at_fraction(sa).bounds(b));
    out.extend(at_fraction(sb).bounds(b));
  } else {
    // Speed of the rotating part R(s) S(s) p for the box's corners (its largest value over the box): the rotation
    // turns at 2 * half_angle per unit s, and S changes by S1 - S0.
    double reach = 0.0, stretch_speed = 0.0;
    Mat3d ds{};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) ds[i][j] = key_[1].stretch[i][j] - key_[0].stretch[i][j];
    for (int c = 0; c < 8; ++c) {
      const auto p = corner(b, c);
      reach = std::max({reach, length3(apply3(key_[0].stretch, p)), length3(apply3(key_[1].stretch, p))});
      stretch_speed = std::max(stretch_speed, length3(apply3(ds, p)));
    }
    const double speed = 2.0 * half_angle_ * reach + stretch_speed;
    const int pieces = std::max(1, int(std::ceil((sb - sa) * 2.0 * half_angle_ / kBoundsMaxTurn)));
    const double h = (sb - sa) / pieces;
    for (int i = 0; i < pieces; ++i) {
      const double s0 = sa + h * i, s1 = i + 1 == pieces ? sb : s0 + h, sm = 0.5 * (s0 + s1);
      // Translation is linear in s: its two ends bound it exactly. The rotating part stays within `speed * h / 2`
      // of where it is at the middle of the piece.
      Bounds3f moved;
      const Transform mid = at_fraction(sm);
      const Vec3f t_mid(mid.matrix().m[0][3], mid.matrix().m[1][3], mid.matrix().m[2][3]);
      for (int c = 0; c < 8; ++c) {
        const auto p = corner(b, c);
        moved.extend(mid.point(Vec3f(float(p[0]), float(p[1]), float(p[2]))) - t_mid);
      }
      Bounds3f translation;
      for (double s : {s0, s1}) {
        Vec3f t;
        for (size_t k = 0; k < 3; ++k)
          t[int(k)] = float((1.0 - s) * key_[0].translation[k] + s * key_[1].translation[k]);
        translation.extend(t);
      }
      const float pad = float(speed * h * 0.5);
      out.extend(Bounds3f(translation.lo + moved.lo - Vec3f(pad), translation.hi + moved.hi + Vec3f(pad)));
    }
  }
  const float round = float(kBoundsRoundingPad) * std::max(max_component(abs(out.lo)), max_component(abs(out.hi)));
  return Bounds3f(out.lo - Vec3f(round), out.hi + Vec3f(round));
}

}  // namespace kiln
