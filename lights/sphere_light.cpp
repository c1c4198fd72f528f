#include "lights/sphere_light.h"

#include "core/error.h"

namespace kiln {

namespace {

// A query point closer to the surface than this (relative to r^2 in object space) counts as on it: a cone of
// nearly 90 degrees would only find grazing points of the shell around q, which emit nothing useful towards it.
constexpr double kOnSurfaceTolerance = 1e-4;
// Directions within this relative band outside the silhouette still count as hitting the sphere in pdf_li, so a
// BSDF ray the accelerator reported as a hit is not given pdf 0 because of rounding.
constexpr double kSilhouetteTolerance = 1e-4;
// Knud Thomsen's exponent for the ellipsoid surface area approximation.
constexpr double kThomsenP = 1.6075;
constexpr double kPiD = 3.14159265358979323846;

// Double-precision 3-vectors: the cone construction divides by sin(theta_max) and the transforms mix large
// and small magnitudes, so the geometry is done in double and only the results are rounded to float.
struct D3 {
  double x = 0, y = 0, z = 0;
  D3() = default;
  D3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  explicit D3(Vec3f v) : x(v.x), y(v.y), z(v.z) {}
  D3 operator+(D3 b) const { return {x + b.x, y + b.y, z + b.z}; }
  D3 operator-(D3 b) const { return {x - b.x, y - b.y, z - b.z}; }
  D3 operator*(double s) const { return {x * s, y * s, z * s}; }
  D3 operator-() const { return {-x, -y, -z}; }
  Vec3f to_float() const { return {float(x), float(y), float(z)}; }
  std::array<double, 3> arr() const { return {x, y, z}; }
};
double sqr_d(double x) { return x * x; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(D3 a) { return std::sqrt(dot(a, a)); }
D3 normalize(D3 a) { return a * (1.0 / length(a)); }

using Affine = std::array<double, 12>;
D3 apply_point(const Affine& m, D3 p) {
  return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
          m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
}
D3 apply_vector(const Affine& m, D3 v) {
  return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
          m[8] * v.x + m[9] * v.y + m[10] * v.z};
}
// Normals transform by the inverse transpose: n_world = (M^-1)^T n, with inv = M^-1.
D3 apply_normal(const Affine& inv, D3 n) {
  return {inv[0] * n.x + inv[4] * n.y + inv[8] * n.z, inv[1] * n.x + inv[5] * n.y + inv[9] * n.z,
          inv[2] * n.x + inv[6] * n.y + inv[10] * n.z};
}
Affine affine_of(const Mat4& m) {
  Affine a{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) a[size_t(4 * r + c)] = m.m[size_t(r)][size_t(c)];
  return a;
}
double det3(const Affine& m) {
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
         m[2] * (m[4] * m[9] - m[5] * m[8]);
}

// Eigenvalues of the symmetric 3x3 matrix A = M^T M (the squared singular values of M), closed form
// (Smith 1961).
std::array<double, 3> squared_singular_values(const Affine& m) {
  double a[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += m[size_t(4 * k + i)] * m[size_t(4 * k + j)];
      a[i][j] = s;
    }
  const double p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
  const double q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
  const double p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) + (a[2][2] - q) * (a[2][2] - q) +
                    2.0 * p1;
  if (p2 <= 1e-30 * q * q) return {q, q, q};
  const double p = std::sqrt(p2 / 6.0);
  double b[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) b[i][j] = (a[i][j] - (i == j ? q : 0.0)) / p;
  const double det_b = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) -
                       b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                       b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
  const double phi = std::acos(std::clamp(det_b / 2.0, -1.0, 1.0)) / 3.0;
  const double e1 = q + 2.0 * p * std::cos(phi);
  const double e3 = q + 2.0 * p * std::cos(phi + 2.0 * kPiD / 3.0);
  return {e1, 3.0 * q - e1 - e3, e3};
}

double ellipsoid_area(double a, double b, double c) {
  const double ap = std::pow(a, kThomsenP), bp = std::pow(b, kThomsenP), cp = std::pow(c, kThomsenP);
  return 4.0 * kPiD * std::pow((ap * bp + ap * cp + bp * cp) / 3.0, 1.0 / kThomsenP);
}

}  // namespace

struct SphereLight::Local {
  D3 q;            // query point in object space
  D3 to_center;    // center - q
  double dist2;    // |center - q|^2
  bool inside;     // inside or on the surface
};

SphereLight::SphereLight(Vec3f center, float radius, const Transform& to_world, Rgb radiance, EllipsoidPdf density)
    : center_(center), radius_(radius), radiance_(radiance), course_pdf_(density == EllipsoidPdf::CourseObjectSpace) {
  if (!(radius > 0.0f) || !std::isfinite(radius)) throw Error("LightSphere: Radius must be positive");
  to_world_ = affine_of(to_world.matrix());
  to_object_ = affine_of(to_world.inverse_matrix());
  abs_det_ = std::abs(det3(to_world_));
  if (!(abs_det_ > 0.0) || !std::isfinite(abs_det_))
    throw Error("LightSphere: its transformation is singular (zero scale)");
  const auto s2 = squared_singular_values(to_world_);
  const double r = radius;
  surface_area_ = float(ellipsoid_area(r * std::sqrt(std::max(0.0, s2[0])), r * std::sqrt(std::max(0.0, s2[1])),
                                       r * std::sqrt(std::max(0.0, s2[2]))));
}

SphereLight::Local SphereLight::to_local(Vec3f q) const {
  Local l;
  l.q = apply_point(to_object_, D3(q));
  l.to_center = D3(center_) - l.q;
  l.dist2 = dot(l.to_center, l.to_center);
  l.inside = l.dist2 <= double(radius_) * double(radius_) * (1.0 + kOnSurfaceTolerance);
  return l;
}

bool SphereLight::contains(Vec3f p) const { return to_local(p).inside; }

// The ellipsoid M (center + r x) + t, |x| = 1, reaches r |row i of M| either side of its center along world axis i.
Bounds3f SphereLight::world_bounds() const {
  const D3 c = apply_point(to_world_, D3(center_));
  double half[3];
  for (size_t i = 0; i < 3; ++i)
    half[i] = double(radius_) * std::sqrt(sqr_d(to_world_[4 * i]) + sqr_d(to_world_[4 * i + 1]) + sqr_d(to_world_[4 * i + 2]));
  const D3 h(half[0], half[1], half[2]);
  return Bounds3f((c - h).to_float(), (c + h).to_float());
}

// The map w_obj -> w_world = M w_obj / |M w_obj| has solid-angle Jacobian |det M| / |M w_obj|^3, so
// p_world = p_obj |M w_obj|^3 / |det M| = p_obj / (|det M| |M^-1 w_world|^3) for unit w_world. This equals
// p_A,obj / J * d_world^2 / |cos_world| with J = |det M| |M^-T n_obj| (the cosines and distances cancel exactly),
// but stays finite and accurate at the silhouette where both cosines go to zero.
double SphereLight::solid_angle_scale(const std::array<double, 3>& wi) const {
  const double l = length(apply_vector(to_object_, D3(wi[0], wi[1], wi[2])));
  return 1.0 / (abs_det_ * l * l * l);
}

std::optional<LightSample> SphereLight::sample_li(const LightQuery& q, Vec2f u) const {
  const Local l = to_local(q.p);
  if (l.inside) return sample_area(q, u);

  // Cone subtended by the sphere from q (object space), sampled uniformly; the point on the sphere is built
  // from the angle alpha at the center (pbrt-v4 Sphere::Sample) instead of re-intersecting the ray in float.
  const double r = radius_;
  const double sin2_max = r * r / l.dist2;
  const double sin_max = std::sqrt(sin2_max);
  const double one_minus_cos_max = sin2_max / (1.0 + std::sqrt(1.0 - sin2_max));  // = 1 - cos, no cancellation
  const double one_minus_cos = double(u.x) * one_minus_cos_max;
  const double sin2 = one_minus_cos * (2.0 - one_minus_cos);
  const double cos_t = 1.0 - one_minus_cos;
  const double cos_alpha = sin2 / sin_max + cos_t * std::sqrt(std::max(0.0, 1.0 - sin2 / sin2_max));
  const double sin_alpha = std::sqrt(std::max(0.0, 1.0 - cos_alpha * cos_alpha));
  const double phi = 2.0 * kPiD * double(u.y);

  const D3 axis = l.to_center * (1.0 / std::sqrt(l.dist2));
  // Orthonormal basis around the axis (Duff et al.), in double.
  const double sign = std::copysign(1.0, axis.z);
  const double a = -1.0 / (sign + axis.z);
  const double b = axis.x * axis.y * a;
  const D3 s(1.0 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
  const D3 t(b, sign + axis.y * axis.y * a, -axis.y);
  const D3 n_obj = -(s * (sin_alpha * std::cos(phi)) + t * (sin_alpha * std::sin(phi)) + axis * cos_alpha);
  const D3 p_obj = D3(center_) + n_obj * r;

  const D3 q_world(q.p);
  const D3 p_world = apply_point(to_world_, p_obj);
  const D3 to_light = p_world - q_world;
  const double d = length(to_light);
  if (!(d > 0.0) || !std::isfinite(d)) return std::nullopt;
  const D3 wi = to_light * (1.0 / d);
  const double scale = course_pdf_ ? 1.0 : solid_angle_scale(wi.arr());
  const double pdf = scale / (2.0 * kPiD * one_minus_cos_max);
  if (!(pdf > 0.0) || !std::isfinite(pdf)) return std::nullopt;

  LightSample smp;
  smp.li = radiance_;
  smp.wi = wi.to_float();
  smp.p_light = p_world.to_float();
  smp.n_light = normalize(apply_normal(to_object_, n_obj)).to_float();
  smp.distance = float(d);
  smp.pdf = float(pdf);
  return smp;
}

std::optional<LightSample> SphereLight::sample_area(const LightQuery& q, Vec2f u) const {
  // Uniform direction from the center = uniform object-space area.
  const double z = 1.0 - 2.0 * double(u.x);
  const double rad = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPiD * double(u.y);
  const D3 n_obj(rad * std::cos(phi), rad * std::sin(phi), z);
  const D3 p_world = apply_point(to_world_, D3(center_) + n_obj * double(radius_));
  const Vec3f p = p_world.to_float();
  const float pdf = pdf_area(q, p);
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;  // faces away from q, or degenerate
  const D3 to_light = p_world - D3(q.p);
  const double d = length(to_light);
  LightSample smp;
  smp.li = radiance_;
  smp.wi = (to_light * (1.0 / d)).to_float();
  smp.p_light = p;
  smp.n_light = normalize(apply_normal(to_object_, n_obj)).to_float();
  smp.distance = float(d);
  smp.pdf = pdf;
  return smp;
}

float SphereLight::pdf_area(const LightQuery& q, Vec3f p_light) const {
  const D3 p_world(p_light);
  const D3 n_obj = normalize(apply_point(to_object_, p_world) - D3(center_));
  const D3 m_n = apply_normal(to_object_, n_obj);  // M^-T n_obj
  const double m_n_len = length(m_n);
  const D3 to_light = p_world - D3(q.p);
  const double d2 = dot(to_light, to_light);
  if (!(d2 > 0.0) || !(m_n_len > 0.0)) return 0.0f;
  const double cos_l = -dot(m_n, to_light) / (m_n_len * std::sqrt(d2));
  if (!(cos_l > 0.0)) return 0.0f;
  // Uniform in object area: p_A,obj = 1 / (4 pi r^2); world area density p_A,obj / J, J = |det M| |M^-T n_obj|.
  const double r = radius_;
  const double pdf_area_world = 1.0 / (4.0 * kPiD * r * r * abs_det_ * m_n_len);
  return float(pdf_area_world * d2 / cos_l);
}

float SphereLight::pdf_li(const LightQuery& q, Vec3f p_light, Vec3f, uint32_t) const {
  const Local l = to_local(q.p);
  if (l.inside) return pdf_area(q, p_light);
  const D3 to_light = D3(p_light) - D3(q.p);
  const double len = length(to_light);
  if (!(len > 0.0)) return 0.0f;
  const D3 wi = to_light * (1.0 / len);
  // Does the ray q + t wi hit the sphere? (object space, where it is a ray towards the sphere's cone)
  const D3 v = normalize(apply_vector(to_object_, wi));
  const double along = dot(v, l.to_center);
  if (!(along > 0.0)) return 0.0f;
  const D3 perp = l.to_center - v * along;
  const double r = radius_;
  if (dot(perp, perp) > r * r * (1.0 + kSilhouetteTolerance)) return 0.0f;
  const double sin2_max = r * r / l.dist2;
  const double one_minus_cos_max = sin2_max / (1.0 + std::sqrt(1.0 - sin2_max));
  return float((course_pdf_ ? 1.0 : solid_angle_scale(wi.arr())) / (2.0 * kPiD * one_minus_cos_max));
}

}  // namespace kiln
