#include "renderer/world/camera.h"

#include "core/equal_area.h"
#include "core/error.h"
#include "core/sampling.h"
#include "renderer/world/lens_system.h"

namespace kiln {
namespace {

// Up need not be perpendicular to gaze: re-orthogonalise through the cross products.
bool make_frame(Vec3f gaze, Vec3f up, bool left_handed, Vec3f& u, Vec3f& v, Vec3f& w) {
  if (!(length(gaze) > 0.0f)) return false;
  w = -normalize(gaze);
  const Vec3f uu = left_handed ? cross(w, up) : cross(up, w);
  if (!(length(uu) > 0.0f)) return false;
  u = normalize(uu);
  v = left_handed ? cross(u, w) : cross(w, u);
  return true;
}

// World from camera space (x along u, y along v, z along -w) with the eye at e.
Transform frame_transform(Vec3f e, Vec3f u, Vec3f v, Vec3f w) {
  Mat4 m = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[size_t(i)][0] = u[i];
    m.m[size_t(i)][1] = v[i];
    m.m[size_t(i)][2] = -w[i];
    m.m[size_t(i)][3] = e[i];
  }
  return Transform::from_matrix(m);
}

}  // namespace

Camera::Camera(const CameraDesc& c)
    : projection_(c.projection), mapping_(c.spherical_mapping), near_(c.near_distance), width_(c.width),
      height_(c.height), full_width_(c.full_width > 0 ? c.full_width : c.width),
      full_height_(c.full_height > 0 ? c.full_height : c.height), crop_x_(c.crop_x), crop_y_(c.crop_y),
      aperture_(c.aperture_size), focus_(c.focus_distance), disk_lens_(c.disk_lens), film_scale_(c.film_scale),
      max_component_(c.max_component) {
  if (width_ <= 0 || height_ <= 0) throw Error("camera " + c.id + ": image resolution must be positive");
  frame_.e = c.position;
  if (!(length(c.gaze) > 0.0f)) throw Error("camera " + c.id + ": gaze has zero length");
  if (!make_frame(c.gaze, c.up, c.left_handed, frame_.u, frame_.v, frame_.w))
    throw Error("camera " + c.id + ": up is parallel to gaze");
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
  if (c.motion) {
    Frame end{c.motion->position, {}, {}, {}};
    if (!make_frame(c.motion->gaze, c.motion->up, c.left_handed, end.u, end.v, end.w))
      throw Error("camera " + c.id + ": its end pose has a zero gaze or an up parallel to it");
    try {
      motion_ = AnimatedTransform(frame_transform(frame_.e, frame_.u, frame_.v, frame_.w), c.motion->start_time,
                                  frame_transform(end.e, end.u, end.v, end.w), c.motion->end_time);
    } catch (const Error& e) {
      throw Error("camera " + c.id + ": motion: " + e.what());
    }
  }
  if (projection_ == CameraProjection::Realistic) {
    if (!c.lens) throw Error("camera " + c.id + ": a realistic camera needs a lens system");
    const std::string where = (c.lens->directive.empty() ? "camera " + c.id : c.lens->directive) + ", lens file " +
                              c.lens->file;
    lens_ = std::make_unique<LensSystem>(*c.lens, full_width_, full_height_, where);
  }
}

Camera::~Camera() = default;
Camera::Camera(Camera&&) noexcept = default;

bool Camera::has_aperture() const { return aperture_ > 0.0f || projection_ == CameraProjection::Realistic; }

Camera::Frame Camera::frame_at(float time) const {
  if (!motion_.animated()) return frame_;
  const Transform m = motion_.at(time);
  return {m.point({0, 0, 0}), normalize(m.vector({1, 0, 0})), normalize(m.vector({0, 1, 0})),
          -normalize(m.vector({0, 0, 1}))};
}

Ray Camera::perspective(const Frame& f, float x, float y, Vec2f lens) const {
  const float su = l_ + x * (r_ - l_) / float(width_);
  const float sv = t_ - y * (t_ - b_) / float(height_);
  const Vec3f dir = f.u * su + f.v * sv - f.w * near_;
  if (aperture_ <= 0.0f) return Ray{f.e, normalize(dir), 0.0f, kInfinity};
  // Thin lens (course reading): lens point on a square of side ApertureSize centred at e in the (u, v) plane;
  // the point in focus lies on the plane at FocusDistance along the gaze.
  const float scale = focus_ / near_;
  const Vec3f focus_point = f.e + dir * scale;
  // pbrt's thin lens: a disk of diameter aperture_ (concentric map), same focus plane.
  const Vec2f d = disk_lens_ ? sample_uniform_disk_concentric(lens) * 0.5f : Vec2f(lens.x - 0.5f, lens.y - 0.5f);
  const Vec3f origin = f.e + f.u * (d.x * aperture_) + f.v * (d.y * aperture_);
  return Ray{origin, normalize(focus_point - origin), 0.0f, kInfinity};
}

Ray Camera::orthographic(const Frame& f, float x, float y, Vec2f lens) const {
  const float su = l_ + x * (r_ - l_) / float(width_);
  const float sv = t_ - y * (t_ - b_) / float(height_);
  if (aperture_ <= 0.0f) return Ray{f.e + f.u * su + f.v * sv, -f.w, 0.0f, kInfinity};
  const Vec2f d = sample_uniform_disk_concentric(lens) * (0.5f * aperture_);
  const Vec3f origin = f.e + f.u * d.x + f.v * d.y;
  const Vec3f focus_point = f.e + f.u * su + f.v * sv - f.w * focus_;
  return Ray{origin, normalize(focus_point - origin), 0.0f, kInfinity};
}

Vec2f Camera::full_film(float x, float y) const {
  return {(x + float(crop_x_)) / float(full_width_), (y + float(crop_y_)) / float(full_height_)};
}

// Camera-space direction (x, y, z) of a spherical camera's film point.
Vec3f Camera::spherical_direction(float x, float y) const {
  const Vec2f uv = full_film(x, y);
  Vec3f d;
  if (mapping_ == SphericalMapping::Equirectangular) {
    const float theta = kPi * uv.y, phi = 2.0f * kPi * uv.x;
    d = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
  } else {
    d = equal_area_square_to_sphere(wrap_equal_area_square(uv));
  }
  return {d.x, d.z, d.y};  // the mapping's pole is the camera's up
}

CameraRay Camera::sample(float x, float y, Vec2f lens, float time) const {
  const Frame f = frame_at(time);
  CameraRay out;
  out.weight = film_scale_;
  const auto to_world = [&](Vec3f v) { return f.u * v.x + f.v * v.y - f.w * v.z; };
  switch (projection_) {
    case CameraProjection::Perspective: out.ray = perspective(f, x, y, lens); break;
    case CameraProjection::Orthographic: out.ray = orthographic(f, x, y, lens); break;
    case CameraProjection::Spherical: out.ray = Ray{f.e, normalize(to_world(spherical_direction(x, y)))}; break;
    case CameraProjection::Realistic: {
      Ray r;
      const float w = lens_->generate(full_film(x, y), lens, r);
      out.weight *= w;
      out.ray = w > 0.0f ? Ray{f.e + to_world(r.o), normalize(to_world(r.d))} : Ray{f.e, -f.w};
      break;
    }
  }
  out.ray.time = time;
  return out;
}

CameraSpread Camera::pixel_spread() const {
  CameraSpread s;
  const Frame& f = frame_;
  if (projection_ == CameraProjection::Perspective) {
    // A pixel step moves the image-plane point by (r - l) / width along u (film y: (t - b) / height against v); at
    // unit distance along the axis that is the same divided by NearDistance. A thin lens's neighbouring rays share
    // the lens point and aim at focus-plane points one pixel apart: the same angle, no change of origin.
    s.origin = f.e;
    s.axis = -f.w;
    s.dir_dx = f.u * ((r_ - l_) / (float(width_) * near_));
    s.dir_dy = f.v * (-(t_ - b_) / (float(height_) * near_));
    return s;
  }
  if (projection_ == CameraProjection::Orthographic && aperture_ <= 0.0f) {
    s.origin = f.e;
    s.axis = -f.w;
    s.pos_dx = f.u * ((r_ - l_) / float(width_));
    s.pos_dy = f.v * (-(t_ - b_) / float(height_));
    return s;
  }
  // Otherwise by differences of the rays through the film centre and one pixel beside it (the lens centre).
  const float cx = 0.5f * float(width_), cy = 0.5f * float(height_);
  const Ray r0 = generate_ray(cx, cy, {0.5f, 0.5f}), rx = generate_ray(cx + 1, cy, {0.5f, 0.5f}),
            ry = generate_ray(cx, cy + 1, {0.5f, 0.5f});
  s.origin = r0.o;
  s.axis = r0.d;
  const auto along_axis = [&](Vec3f d) { return d / dot(d, r0.d); };
  s.dir_dx = along_axis(rx.d) - r0.d;
  s.dir_dy = along_axis(ry.d) - r0.d;
  s.pos_dx = rx.o - r0.o;
  s.pos_dy = ry.o - r0.o;
  return s;
}

}  // namespace kiln
