// A transform that moves over the shutter interval, interpolated as pbrt-v4 interpolates its AnimatedTransform:
// each keyframe is decomposed into a translation T, a rotation R (a unit quaternion) and a symmetric stretch S
// (the polar decomposition of the linear part, M = T R S); T and S are interpolated linearly and R by spherical
// linear interpolation along the shorter arc. Before the start time the start transform holds, after the end time
// the end transform (pbrt's clamping). A mirroring keyframe (negative determinant) is decomposed with R = -Q and
// S = -P for its polar factors Q P, so that R is a proper rotation; both keyframes must mirror alike.
#pragma once
#include <array>

#include "core/bounds.h"
#include "core/transform.h"

namespace kiln {

class AnimatedTransform {
 public:
  AnimatedTransform() = default;  // the identity, not animated
  explicit AnimatedTransform(const Transform& fixed) : start_(fixed), end_(fixed) {}
  // Throws kiln::Error when a keyframe is singular or only one of them mirrors (no rotation path joins them).
  AnimatedTransform(const Transform& start, float start_time, const Transform& end, float end_time);

  // False when both keyframes are the same transform (at() is then always it).
  bool animated() const { return animated_; }
  const Transform& start() const { return start_; }
  const Transform& end() const { return end_; }
  float start_time() const { return t0_; }
  float end_time() const { return t1_; }
  Transform at(float time) const;
  // The angle (radians) the rotation turns through between the keyframes.
  float rotation_angle() const { return float(2.0 * half_angle_); }

  // A box holding b's image at every time in [t0, t1] (conservative: an arc swept by a rotation is bounded by the
  // rotation's speed over short sub-intervals; translation and stretch alone are exact, the image moves affinely).
  Bounds3f motion_bounds(const Bounds3f& b, float t0, float t1) const;
  Bounds3f motion_bounds(const Bounds3f& b) const { return motion_bounds(b, t0_, t1_); }

 private:
  struct Keyframe {
    std::array<double, 3> translation{};
    std::array<double, 4> rotation{0, 0, 0, 1};  // x y z w
    std::array<std::array<double, 3>, 3> stretch{};
  };
  Transform at_fraction(double s) const;
  double fraction(float time) const;

  Transform start_, end_;
  float t0_ = 0.0f, t1_ = 1.0f;
  bool animated_ = false;
  std::array<Keyframe, 2> key_{};
  double half_angle_ = 0.0;  // angle between the two unit quaternions
};

}  // namespace kiln
