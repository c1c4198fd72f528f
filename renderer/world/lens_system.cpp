#include "renderer/world/lens_system.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

#include "core/error.h"
#include "materials/fresnel.h"

namespace kiln {
namespace {

// The thick-lens rays run parallel to the axis at this fraction of the film diagonal.
constexpr float kParaxialHeight = 0.001f;
// The exit pupil is searched over this multiple of the rear element's radius.
constexpr float kPupilSearchScale = 1.5f;

// Van der Corput in base 2 and 3: the first two Halton dimensions.
float radical_inverse_2(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return std::min(float(i) * 0x1p-32f, kOneMinusEpsilon);
}
float radical_inverse_3(uint32_t i) {
  double inv = 1.0 / 3.0, f = inv, r = 0.0;
  for (; i > 0; i /= 3, f *= inv) r += f * double(i % 3);
  return std::min(float(r), kOneMinusEpsilon);
}

// Where a ray meets the spherical interface of radius `radius` centred on the axis at z_center: the nearer or the
// farther crossing, whichever lies on the interface's cap that faces the ray. n faces back along the ray.
std::optional<float> hit_sphere(float radius, float z_center, const Ray& r, Vec3f& n) {
  const Vec3f o = r.o - Vec3f(0, 0, z_center);
  const float a = dot(r.d, r.d), b = 2.0f * dot(r.d, o), c = dot(o, o) - radius * radius;
  const double disc = double(b) * b - 4.0 * double(a) * c;
  if (disc < 0.0 || !(a > 0.0f)) return std::nullopt;
  const double root = std::sqrt(disc);
  const double q = b < 0 ? -0.5 * (b - root) : -0.5 * (b + root);
  if (q == 0.0) return std::nullopt;
  double t0 = q / a, t1 = c / q;
  if (t0 > t1) std::swap(t0, t1);
  const bool nearer = (r.d.z > 0.0f) != (radius < 0.0f);
  const float t = float(nearer ? t0 : t1);
  if (!(t >= 0.0f)) return std::nullopt;
  n = face_forward(normalize(o + r.d * t), -r.d);
  return t;
}

// Where the ray crosses the film-side interface i at axial position z: a plane for the stop, a sphere otherwise.
std::optional<float> cross_interface(const LensInterfaceDesc& e, float z, const Ray& r, Vec3f& n) {
  if (e.curvature_radius == 0.0f) {
    const float t = (z - r.o.z) / r.d.z;
    if (!(t >= 0.0f)) return std::nullopt;
    return t;
  }
  return hit_sphere(e.curvature_radius, z + e.curvature_radius, r, n);
}

float medium_eta(float eta) { return eta == 0.0f ? 1.0f : eta; }

Ray flip_z(const Ray& r) { return Ray{{r.o.x, r.o.y, -r.o.z}, {r.d.x, r.d.y, -r.d.z}, r.tmin, r.tmax, r.time}; }

// Focal point and principal plane (their z) of the system for a ray that entered parallel to the axis (pbrt's
// cardinal points, in the camera space's z negated as the lens system's).
void cardinal_points(const Ray& in, const Ray& out, float& pz, float& fz) {
  const float tf = -out.o.x / out.d.x;
  fz = -(out.o.z + out.d.z * tf);
  const float tp = (in.o.x - out.o.x) / out.d.x;
  pz = -(out.o.z + out.d.z * tp);
}

// Moves r onto interface e (its vertex at z) and refracts it from eta_i into eta_t; false when the interface or
// its aperture stops the ray or it is totally reflected.
bool pass_interface(const LensInterfaceDesc& e, float z, float eta_i, float eta_t, Ray& r) {
  Vec3f n;
  const auto t = cross_interface(e, z, r, n);
  if (!t) return false;
  const Vec3f p = r.at(*t);
  if (p.x * p.x + p.y * p.y > e.aperture_radius * e.aperture_radius) return false;
  r.o = p;
  if (e.curvature_radius == 0.0f) return true;  // the aperture stop: no glass
  const auto refracted = refract(normalize(-r.d), n, eta_t / eta_i);
  if (!refracted) return false;
  r.d = refracted->wt;
  return true;
}

}  // namespace

LensSystem::LensSystem(const LensSystemDesc& desc, int full_width, int full_height, const std::string& where,
                       int pupil_samples)
    : interfaces_(desc.interfaces), diagonal_(desc.film_diagonal) {
  if (interfaces_.empty()) throw Error(where + ": " + "the lens system has no interfaces");
  if (!(diagonal_ > 0.0f)) throw Error(where + ": " + "the film diagonal must be positive");
  const float aspect = float(full_height) / float(full_width);
  const float x = std::sqrt(diagonal_ * diagonal_ / (1.0f + aspect * aspect));
  film_size_ = {x, aspect * x};
  focus(desc.focus_distance, where);
  pupil_.resize(kExitPupilRings);
  tbb::parallel_for(0, kExitPupilRings, [&](int i) {
    const float r0 = float(i) / kExitPupilRings * diagonal_ / 2.0f;
    const float r1 = float(i + 1) / kExitPupilRings * diagonal_ / 2.0f;
    pupil_[size_t(i)] = bound_exit_pupil(r0, r1, uint32_t(std::max(1, pupil_samples)));
  });
  bool any = false;
  for (const PupilBounds& b : pupil_) any |= !b.empty();
  if (!any) throw Error(where + ": " + "no ray from the film passes through the lens system (is the aperture closed?)");
}

float LensSystem::front_z() const {
  float z = 0.0f;
  for (const LensInterfaceDesc& e : interfaces_) z += e.thickness;
  return z;
}

float LensSystem::trace_from_film(const Ray& camera_ray, Ray* out) const {
  float z = 0.0f;
  Ray r = flip_z(camera_ray);
  for (size_t k = interfaces_.size(); k-- > 0;) {
    z -= interfaces_[k].thickness;
    // From the glass behind the interface (its own eta) into the one in front of it.
    const float eta_i = medium_eta(interfaces_[k].eta), eta_t = k > 0 ? medium_eta(interfaces_[k - 1].eta) : 1.0f;
    if (!pass_interface(interfaces_[k], z, eta_i, eta_t, r)) return 0.0f;
  }
  if (out) *out = flip_z(r);
  return 1.0f;
}

float LensSystem::trace_from_scene(const Ray& camera_ray, Ray* out) const {
  float z = -front_z();
  Ray r = flip_z(camera_ray);
  for (size_t k = 0; k < interfaces_.size(); ++k) {
    const float eta_i = k == 0 ? 1.0f : medium_eta(interfaces_[k - 1].eta), eta_t = medium_eta(interfaces_[k].eta);
    if (!pass_interface(interfaces_[k], z, eta_i, eta_t, r)) return 0.0f;
    z += interfaces_[k].thickness;
  }
  if (out) *out = flip_z(r);
  return 1.0f;
}

void LensSystem::focus(float focus_distance, const std::string& where) {
  const float x = kParaxialHeight * diagonal_;
  float pz[2], fz[2];
  const Ray from_scene{{x, 0.0f, front_z() + 1.0f}, {0, 0, -1}};
  Ray to_film;
  if (!trace_from_scene(from_scene, &to_film))
    throw Error(where + ": " + "no ray parallel to the axis passes the lens from the scene (is the aperture stop tiny?)");
  cardinal_points(from_scene, to_film, pz[0], fz[0]);
  const Ray from_film{{x, 0.0f, rear_z() - 1.0f}, {0, 0, 1}};
  Ray to_scene;
  if (!trace_from_film(from_film, &to_scene))
    throw Error(where + ": " + "no ray parallel to the axis passes the lens from the film (is the aperture stop tiny?)");
  cardinal_points(from_film, to_scene, pz[1], fz[1]);
  // Thin-lens equation of the thick-lens approximation, solved for the film's shift delta (in double: far focus
  // distances cancel to a few millimetres).
  const double f = double(fz[0]) - pz[0], z = -double(focus_distance);
  const double c = (pz[1] - z - pz[0]) * (pz[1] - z - 4.0 * f - pz[0]);
  if (!(c > 0.0))
    throw Error(where + ": " + "the lens cannot focus at " + std::to_string(focus_distance) +
                           " m (nearer than it allows, or its focal length is not positive)");
  // (pz1 - z + pz0 - sqrt(c)) / 2, with the difference of the two large terms written without cancellation.
  const double a = pz[1] - z - pz[0];
  const double delta = 0.5 * (2.0 * pz[0] + 4.0 * f * a / (a + std::sqrt(c)));  // a^2 - c = 4 f a
  interfaces_.back().thickness += float(delta);
  if (!(interfaces_.back().thickness > 0.0f))
    throw Error(where + ": " + "focused at " + std::to_string(focus_distance) + " m the film would lie inside the lens");
}

PupilBounds LensSystem::bound_exit_pupil(float film_x0, float film_x1, uint32_t samples) const {
  PupilBounds b;
  const float rear = kPupilSearchScale * interfaces_.back().aperture_radius;
  for (uint32_t i = 0; i < samples; ++i) {
    const float fx = film_x0 + (film_x1 - film_x0) * ((float(i) + 0.5f) / float(samples));
    const Vec3f film{fx, 0.0f, 0.0f};
    const Vec3f rear_point{-rear + 2.0f * rear * radical_inverse_2(i), -rear + 2.0f * rear * radical_inverse_3(i),
                           rear_z()};
    const bool inside = rear_point.x >= b.lo.x && rear_point.x <= b.hi.x && rear_point.y >= b.lo.y &&
                        rear_point.y <= b.hi.y;
    if (inside || !trace_from_film(Ray{film, rear_point - film}, nullptr)) continue;
    b.lo = {std::min(b.lo.x, rear_point.x), std::min(b.lo.y, rear_point.y)};
    b.hi = {std::max(b.hi.x, rear_point.x), std::max(b.hi.y, rear_point.y)};
  }
  if (b.empty()) return b;
  // Two sample spacings of the search grid beyond the outermost points that passed.
  const float pad = 2.0f * (2.0f * rear * std::sqrt(2.0f)) / std::sqrt(float(samples));
  b.lo = b.lo - Vec2f(pad, pad);
  b.hi = b.hi + Vec2f(pad, pad);
  return b;
}

float LensSystem::generate(Vec2f film, Vec2f u, Ray& ray) const {
  // The film point (mirrored in x: the image is upside down and reversed behind the lens).
  const Vec2f p{-(-0.5f * film_size_.x + film.x * film_size_.x), -0.5f * film_size_.y + film.y * film_size_.y};
  const float radius = std::sqrt(p.x * p.x + p.y * p.y);
  const int ring = std::min(kExitPupilRings - 1, int(radius / (0.5f * diagonal_) * kExitPupilRings));
  const PupilBounds& b = pupil_[size_t(ring)];
  if (b.empty()) return 0.0f;
  const Vec2f lens{b.lo.x + u.x * (b.hi.x - b.lo.x), b.lo.y + u.y * (b.hi.y - b.lo.y)};
  const float pdf = 1.0f / b.area();
  // The bounds were found along +x: turn them to the film point's angle.
  const float sin_t = radius != 0.0f ? p.y / radius : 0.0f, cos_t = radius != 0.0f ? p.x / radius : 1.0f;
  const Vec3f pupil{cos_t * lens.x - sin_t * lens.y, sin_t * lens.x + cos_t * lens.y, rear_z()};
  const Ray from_film{{p.x, p.y, 0.0f}, pupil - Vec3f(p.x, p.y, 0.0f)};
  if (!trace_from_film(from_film, &ray)) return 0.0f;
  ray.d = normalize(ray.d);
  const float cos_theta = normalize(from_film.d).z;
  const float cos2 = cos_theta * cos_theta;
  return cos2 * cos2 / (pdf * rear_z() * rear_z());
}

}  // namespace kiln
