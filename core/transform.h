// Affine/projective 4x4 transforms with a cached inverse. Points use w = 1, directions w = 0, normals the
// inverse transpose.
#pragma once
#include <array>
#include <optional>

#include "core/bounds.h"

namespace kiln {

struct Mat4 {
  std::array<std::array<float, 4>, 4> m{};  // row-major: m[row][col]
  static Mat4 identity();
  Mat4 operator*(const Mat4& b) const;
  Mat4 transposed() const;
  // Inverse computed in double precision; empty when the matrix is singular.
  std::optional<Mat4> inverse() const;
  bool operator==(const Mat4&) const = default;
  bool is_identity() const { return *this == identity(); }
};

class Transform {
 public:
  Transform() : m_(Mat4::identity()), inv_(Mat4::identity()) {}
  Transform(const Mat4& m, const Mat4& inv) : m_(m), inv_(inv) {}
  // Throws kiln::Error when m is singular.
  static Transform from_matrix(const Mat4& m);
  // As pbrt keeps them: a singular m gets an inverse of NaNs (invertible() is then false, and so is that of every
  // product with it), for transforms that only ever map points forward (a mesh flattened onto a plane).
  static Transform from_matrix_maybe_singular(const Mat4& m);
  static Transform translate(Vec3f d);
  static Transform scale(Vec3f s);
  // Rotation by angle degrees about axis (normalised here), right-hand rule.
  static Transform rotate(float angle_deg, Vec3f axis);

  const Mat4& matrix() const { return m_; }
  const Mat4& inverse_matrix() const { return inv_; }
  Transform inverse() const { return {inv_, m_}; }
  Transform operator*(const Transform& b) const { return {m_ * b.m_, b.inv_ * inv_}; }
  bool is_identity() const { return m_.is_identity(); }
  // False for a singular transform (from_matrix_maybe_singular): its inverse, normal() and inverse() are NaN.
  bool invertible() const;
  // True when the transform flips orientation (negative determinant of the linear part).
  bool swaps_handedness() const;

  Vec3f point(Vec3f p) const;
  Vec3f vector(Vec3f v) const;
  Vec3f normal(Vec3f n) const;  // not normalised
  Bounds3f bounds(const Bounds3f& b) const;

 private:
  Mat4 m_, inv_;
};

}  // namespace kiln
