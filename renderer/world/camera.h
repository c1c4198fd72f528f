// Cameras. The frame follows the CENG795 convention (spec §2): w = -gaze, u = up x w, v = w x u (u = w x up for
// left-handed pbrt cameras); camera space has x along u, y along v and z along -w. The projections (pbrt-v4's
// camera types, scenes/scene.h CameraProjection):
//   Perspective   image plane at NearDistance with extent l r b t (NearPlane) or derived from FovY and the aspect
//                 ratio; a thin lens (square of side ApertureSize, or pbrt's disk of that diameter) focused at
//                 FocusDistance along the gaze.
//   Orthographic  rays along the gaze from the screen window (NearPlane, camera-space units) on the plane through
//                 the eye; with a lens, pbrt's rule: from a point of the disk around the eye through the screen
//                 point moved to the focus plane.
//   Spherical     every direction: the full film (x right, y down) as pbrt's equal-area square or as latitude
//                 (y: from +v at the top to -v) and longitude (x: from +u turning towards -w, the gaze, at a
//                 quarter of the width).
//   Realistic     pbrt's lens system (renderer/world/lens_system.h); its rays carry a weight.
// A moving camera (CameraDesc::motion) interpolates its frame between the two poses as pbrt-v4 interpolates
// transforms (core/animated_transform.h), at the ray's shutter time. Every ray's weight includes the film's
// imaging ratio (CameraDesc::film_scale).
#pragma once
#include <memory>

#include "core/animated_transform.h"
#include "core/ray.h"
#include "renderer/texture/footprint.h"
#include "scenes/scene.h"

namespace kiln {

class LensSystem;

// A camera ray and the factor its radiance is multiplied by (0: the lens blocked it; the sample still counts).
struct CameraRay {
  Ray ray;
  float weight = 1.0f;
};

class Camera {
 public:
  // Throws kiln::Error on a description no camera can be made from (naming the camera).
  explicit Camera(const CameraDesc& desc);
  ~Camera();
  Camera(Camera&&) noexcept;

  // The ray through film position (x, y) in pixels (x to the right, y down, continuous) for lens sample `lens` in
  // [0,1)^2 at shutter time `time` in [0, 1) (the ray carries it).
  CameraRay sample(float x, float y, Vec2f lens, float time = 0.0f) const;
  Ray generate_ray(float x, float y, Vec2f lens) const { return sample(x, y, lens).ray; }
  int width() const { return width_; }
  int height() const { return height_; }
  bool has_aperture() const;
  bool moves() const { return motion_.animated(); }
  // A sample's radiance with its largest channel limited to CameraDesc::max_component (hue kept).
  Rgb clamp_sample(Rgb L) const {
    const float m = L.max_component();
    return m > max_component_ ? L * (max_component_ / m) : L;
  }
  // The spread of rays per pixel step near the film centre, for texture footprints (renderer/texture/footprint.h).
  CameraSpread pixel_spread() const;

 private:
  struct Frame {
    Vec3f e, u, v, w;
  };
  Frame frame_at(float time) const;
  Ray perspective(const Frame& f, float x, float y, Vec2f lens) const;
  Ray orthographic(const Frame& f, float x, float y, Vec2f lens) const;
  Vec3f spherical_direction(float x, float y) const;
  Vec2f full_film(float x, float y) const;

  CameraProjection projection_ = CameraProjection::Perspective;
  SphericalMapping mapping_ = SphericalMapping::EqualArea;
  Frame frame_;
  AnimatedTransform motion_;  // world from [u v -w e] when the camera moves
  float l_, r_, b_, t_, near_;
  int width_, height_, full_width_, full_height_, crop_x_, crop_y_;
  float aperture_ = 0.0f, focus_ = 0.0f;
  bool disk_lens_ = false;
  float film_scale_ = 1.0f;
  float max_component_;
  std::unique_ptr<LensSystem> lens_;
};

}  // namespace kiln
