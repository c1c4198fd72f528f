#include "lights/mesh_light.h"

#include <string>

#include "core/error.h"

namespace kiln {

MeshLight::MeshLight(std::span<const Vec3f> positions, std::span<const uint32_t> indices, Rgb radiance,
                     bool two_sided)
    : radiance_(radiance), two_sided_(two_sided) {
  if (indices.size() % 3 != 0)
    throw Error("LightMesh: " + std::to_string(indices.size()) + " vertex indices is not a whole number of triangles");
  tris_.resize(indices.size() / 3);
  std::vector<float> areas(tris_.size());
  double total = 0.0;
  for (size_t i = 0; i < tris_.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      if (indices[3 * i + size_t(k)] >= positions.size())
        throw Error("LightMesh: triangle " + std::to_string(i) + " uses vertex index " +
                    std::to_string(indices[3 * i + size_t(k)]) + " but there are only " +
                    std::to_string(positions.size()) + " vertices");
    Tri& t = tris_[i];
    t.p0 = positions[indices[3 * i]];
    t.p1 = positions[indices[3 * i + 1]];
    t.p2 = positions[indices[3 * i + 2]];
    const Vec3f c = cross(t.p1 - t.p0, t.p2 - t.p0);
    const float len = length(c);
    if (len > 0.0f && std::isfinite(len)) {
      t.area = 0.5f * len;
      t.n = c / len;
    }
    areas[i] = t.area;
    total += double(t.area);
  }
  total_area_ = float(total);
  dist_ = Distribution1D(areas);
}

MeshLight::MeshLight(std::span<const Vec3f> positions, std::span<const uint32_t> indices,
                     std::shared_ptr<const EmissionImage> image, std::vector<std::array<Vec2f, 3>> tri_uvs,
                     bool two_sided)
    : MeshLight(positions, indices, image ? image->mean() : Rgb(0.0f), two_sided) {
  if (!image) throw Error("LightMesh: no emission image");
  if (tri_uvs.size() != tris_.size())
    throw Error("LightMesh: " + std::to_string(tri_uvs.size()) + " triangle (u, v) triplets for " +
                std::to_string(tris_.size()) + " triangles");
  image_ = std::move(image);
  tri_uvs_ = std::move(tri_uvs);
}

std::optional<LightSample> MeshLight::sample_li(const LightQuery& q, Vec2f u) const {
  if (!(total_area_ > 0.0f)) return std::nullopt;
  float pmf = 0.0f, u_tri = 0.0f;
  const size_t i = dist_.sample(u.x, &pmf, &u_tri);
  return sample_on(q, i, pmf, {u_tri, u.y});
}

std::optional<LightSample> MeshLight::sample_triangle_li(const LightQuery& q, size_t i, Vec2f u) const {
  if (i >= tris_.size()) return std::nullopt;
  return sample_on(q, i, 1.0f, u);
}

std::optional<LightSample> MeshLight::sample_on(const LightQuery& q, size_t i, float pmf, Vec2f u) const {
  const Tri& t = tris_[i];
  if (!(pmf > 0.0f) || !(t.area > 0.0f)) return std::nullopt;
  const Vec2f b = sample_uniform_triangle(u);
  const Vec3f p = t.p0 * (1.0f - b.x - b.y) + t.p1 * b.x + t.p2 * b.y;
  const Vec3f to_light = p - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return std::nullopt;
  const float d = std::sqrt(d2);
  const Vec3f wi = to_light / d;
  const float cos_l = two_sided_ ? std::abs(dot(t.n, wi)) : -dot(t.n, wi);
  if (!(cos_l > 0.0f)) return std::nullopt;  // q sees the back (non-emitting) side, or the triangle edge-on
  LightSample s;
  s.li = radiance_at(i, b);
  s.wi = wi;
  s.p_light = p;
  s.n_light = t.n;
  s.distance = d;
  s.pdf = (pmf / t.area) * d2 / cos_l;
  return s;
}

float MeshLight::pdf_li(const LightQuery& q, Vec3f p_light, Vec3f, uint32_t prim) const {
  if (prim >= tris_.size()) return 0.0f;
  return pdf_on(q, p_light, tris_[prim], dist_.pmf(prim));
}

float MeshLight::pdf_triangle_li(const LightQuery& q, Vec3f p_light, size_t i) const {
  if (i >= tris_.size()) return 0.0f;
  return pdf_on(q, p_light, tris_[i], 1.0f);
}

float MeshLight::pdf_on(const LightQuery& q, Vec3f p_light, const Tri& t, float pmf) const {
  if (!(pmf > 0.0f) || !(t.area > 0.0f)) return 0.0f;
  const Vec3f to_light = p_light - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f)) return 0.0f;
  const float cos_l = (two_sided_ ? std::abs(dot(t.n, to_light)) : -dot(t.n, to_light)) / std::sqrt(d2);
  return cos_l > 0.0f ? (pmf / t.area) * d2 / cos_l : 0.0f;
}

}  // namespace kiln
