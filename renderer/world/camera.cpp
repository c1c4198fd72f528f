#include "renderer/world/camera.h"

#include "core/error.h"
#include "core/sampling.h"

namespace kiln {

Camera::Camera(const CameraDesc& c)
    : e_(c.position), near_(c.near_distance), width_(c.width), height_(c.height), aperture_(c.aperture_size),
      focus_(c.focus_distance), disk_lens_(c.disk_lens) {
  if (width_ <= 0 || height_ <= 0) throw Error("camera " + c.id + ": image resolution must be positive");
  if (!(length(c.gaze) > 0.0f)) throw Error("camera " + c.id + ": gaze has zero length");
  w_ = -normalize(c.gaze);
  // Up need not be perpendicular to gaze: re-orthogonalise through the cross products.
  Vec3f u = c.left_handed ? cross(w_, c.up) : cross(c.up, w_);
  if (!(length(u) > 0.0f)) throw Error("camera " + c.id + ": up is parallel to gaze");
  u_ = normalize(u);
  v_ = c.left_handed ? cross(u_, w_) : cross(w_, u_);
  if (c.use_fov) {
    t_ = near_ * std::tan(radians(c.fov_y_deg) * 0.5f);
    b_ = -t_;
    r_ = t_ * float(width_) / float(height_);
    l_ = -r_;
  } else {
    l_ = c.near_plane[0];
    r_ = c.near_plane[1];
    b_ = c.near_plane[2];
    t_ = c.near_plane[3];
  }
}

Ray Camera::generate_ray(float x, float y, Vec2f lens) const {
  const float su = l_ + x * (r_ - l_) / float(width_);
  const float sv = t_ - y * (t_ - b_) / float(height_);
  const Vec3f dir = u_ * su + v_ * sv - w_ * near_;
  if (aperture_ <= 0.0f) return Ray{e_, normalize(dir), 0.0f, kInfinity};
  // Thin lens (course reading): lens point on a square of side ApertureSize centred at e in the (u, v) plane;
  // the point in focus lies on the plane at FocusDistance along the gaze.
  const float scale = focus_ / near_;
  const Vec3f focus_point = e_ + dir * scale;
  // pbrt's thin lens: a disk of diameter aperture_ (concentric map), same focus plane.
  const Vec2f d = disk_lens_ ? sample_uniform_disk_concentric(lens) * 0.5f : Vec2f(lens.x - 0.5f, lens.y - 0.5f);
  const Vec3f origin = e_ + u_ * (d.x * aperture_) + v_ * (d.y * aperture_);
  return Ray{origin, normalize(focus_point - origin), 0.0f, kInfinity};
}

CameraSpread Camera::pixel_spread() const {
  // A pixel step moves the image-plane point by (r - l) / width along u (film y: (t - b) / height against v); at
  // unit distance along the axis that is the same divided by NearDistance. A thin lens's neighbouring rays share the
  // lens point and aim at focus-plane points one pixel apart: the same angle, no change of origin.
  CameraSpread s;
  s.origin = e_;
  s.axis = -w_;
  s.dir_dx = u_ * ((r_ - l_) / (float(width_) * near_));
  s.dir_dy = v_ * (-(t_ - b_) / (float(height_) * near_));
  return s;
}

}  // namespace kiln
