// Pinhole and thin-lens cameras following the CENG795 convention (spec §2): w = -gaze, u = up x w, v = w x u,
// image plane at NearDistance with extent l r b t (NearPlane) or derived from FovY and the aspect ratio.
#pragma once
#include "core/ray.h"
#include "renderer/texture/footprint.h"
#include "scenes/scene.h"

namespace kiln {

class Camera {
 public:
  explicit Camera(const CameraDesc& desc);
  // Ray through film position (x, y) in pixels (x to the right, y down, continuous), lens sample in [0,1)^2.
  Ray generate_ray(float x, float y, Vec2f lens) const;
  int width() const { return width_; }
  int height() const { return height_; }
  bool has_aperture() const { return aperture_ > 0.0f; }
  // The spread of rays per pixel step near the film centre, for texture footprints (renderer/texture/footprint.h).
  CameraSpread pixel_spread() const;

 private:
  Vec3f e_, u_, v_, w_;
  float l_, r_, b_, t_, near_;
  int width_, height_;
  float aperture_ = 0.0f, focus_ = 0.0f;
  bool disk_lens_ = false;
};

}  // namespace kiln
