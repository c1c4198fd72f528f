#include "core/transform.h"

#include <cmath>
#include <limits>

#include "core/error.h"

namespace kiln {

Mat4 Mat4::identity() {
  Mat4 r;
  for (int i = 0; i < 4; ++i) r.m[i][i] = 1.0f;
  return r;
}

Mat4 Mat4::operator*(const Mat4& b) const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(m[i][k]) * double(b.m[k][j]);
      r.m[i][j] = float(s);
    }
  return r;
}

Mat4 Mat4::transposed() const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = m[j][i];
  return r;
}

std::optional<Mat4> Mat4::inverse() const {
  // Gauss-Jordan elimination with partial pivoting in double precision.
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      a[i][j] = m[i][j];
      a[i][j + 4] = (i == j) ? 1.0 : 0.0;
    }
  for (int c = 0; c < 4; ++c) {
    int piv = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
    if (std::abs(a[piv][c]) < 1e-300) return std::nullopt;
    if (piv != c)
      for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[piv][j]);
    const double inv = 1.0 / a[c][c];
    for (int j = 0; j < 8; ++j) a[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = a[r][c];
      if (f == 0.0) continue;
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
    }
  }
  Mat4 out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      out.m[i][j] = float(a[i][j + 4]);
      if (!std::isfinite(out.m[i][j])) return std::nullopt;
    }
  return out;
}

Transform Transform::from_matrix(const Mat4& m) {
  auto inv = m.inverse();
  if (!inv) throw Error("transformation matrix is singular (not invertible)");
  return {m, *inv};
}

Transform Transform::from_matrix_maybe_singular(const Mat4& m) {
  if (auto inv = m.inverse()) return {m, *inv};
  Mat4 nan;
  for (auto& row : nan.m) row.fill(std::numeric_limits<float>::quiet_NaN());
  return {m, nan};
}

bool Transform::invertible() const {
  for (const auto& row : inv_.m)
    for (float x : row)
      if (!std::isfinite(x)) return false;
  return true;
}

Transform Transform::translate(Vec3f d) {
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i][3] = d[i];
    inv.m[i][3] = -d[i];
  }
  return {m, inv};
}

Transform Transform::scale(Vec3f s) {
  if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) throw Error("scaling by zero is not invertible");
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i][i] = s[i];
    inv.m[i][i] = 1.0f / s[i];
  }
  return {m, inv};
}

Transform Transform::rotate(float angle_deg, Vec3f axis) {
  const float len = length(axis);
  if (!(len > 0.0f)) throw Error("rotation axis has zero length");
  const double ax = axis.x / len, ay = axis.y / len, az = axis.z / len;
  const double th = double(angle_deg) * 3.14159265358979323846 / 180.0;
  const double c = std::cos(th), s = std::sin(th), t = 1.0 - c;
  Mat4 m = Mat4::identity();
  m.m[0][0] = float(t * ax * ax + c);
  m.m[0][1] = float(t * ax * ay - s * az);
  m.m[0][2] = float(t * ax * az + s * ay);
  m.m[1][0] = float(t * ax * ay + s * az);
  m.m[1][1] = float(t * ay * ay + c);
  m.m[1][2] = float(t * ay * az - s * ax);
  m.m[2][0] = float(t * ax * az - s * ay);
  m.m[2][1] = float(t * ay * az + s * ax);
  m.m[2][2] = float(t * az * az + c);
  return {m, m.transposed()};
}

bool Transform::swaps_handedness() const {
  const auto& a = m_.m;
  const double det = double(a[0][0]) * (double(a[1][1]) * a[2][2] - double(a[1][2]) * a[2][1]) -
                     double(a[0][1]) * (double(a[1][0]) * a[2][2] - double(a[1][2]) * a[2][0]) +
                     double(a[0][2]) * (double(a[1][0]) * a[2][1] - double(a[1][1]) * a[2][0]);
  return det < 0.0;
}

Vec3f Transform::point(Vec3f p) const {
  const auto& a = m_.m;
  const float x = a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3];
  const float y = a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3];
  const float z = a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3];
  const float w = a[3][0] * p.x + a[3][1] * p.y + a[3][2] * p.z + a[3][3];
  return w == 1.0f ? Vec3f(x, y, z) : Vec3f(x, y, z) / w;
}

Vec3f Transform::vector(Vec3f v) const {
  const auto& a = m_.m;
  return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z, a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
          a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
}

Vec3f Transform::normal(Vec3f n) const {
  const auto& a = inv_.m;  // inverse transpose
  return {a[0][0] * n.x + a[1][0] * n.y + a[2][0] * n.z, a[0][1] * n.x + a[1][1] * n.y + a[2][1] * n.z,
          a[0][2] * n.x + a[1][2] * n.y + a[2][2] * n.z};
}

Bounds3f Transform::bounds(const Bounds3f& b) const {
  Bounds3f r;
  if (b.empty()) return r;
  for (int i = 0; i < 8; ++i)
    r.extend(point(Vec3f((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z)));
  return r;
}

}  // namespace kiln
