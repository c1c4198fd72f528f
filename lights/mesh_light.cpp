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
  find_parallelogram();
}

// Relative tolerance for two triangles to make one parallelogram: their unshared corners' midpoint and their
// shared edge's agree to this fraction of the quad's size, and their normals to this cosine deficit.
constexpr float kParallelogramTolerance = 1e-6f;

void MeshLight::find_parallelogram() {
  if (tris_.size() != 2 || !(tris_[0].area > 0.0f) || !(tris_[1].area > 0.0f)) return;
  if (dot(tris_[0].n, tris_[1].n) < 1.0f - kParallelogramTolerance) return;  // folded, or facing opposite ways
  const std::array<Vec3f, 3> a{tris_[0].p0, tris_[0].p1, tris_[0].p2}, b{tris_[1].p0, tris_[1].p1, tris_[1].p2};
  // The corner of each triangle that the other does not have; the remaining two are the shared diagonal.
  const auto lone = [](const std::array<Vec3f, 3>& t, const std::array<Vec3f, 3>& other) -> int {
    int found = -1;
    for (int i = 0; i < 3; ++i) {
      const bool shared = t[size_t(i)] == other[0] || t[size_t(i)] == other[1] || t[size_t(i)] == other[2];
      if (!shared) {
        if (found >= 0) return -1;
        found = i;
      }
    }
    return found;
  };
  const int ia = lone(a, b), ib = lone(b, a);
  if (ia < 0 || ib < 0) return;
  const Vec3f corner = a[size_t(ia)], opposite = b[size_t(ib)];
  const Vec3f s1 = a[size_t((ia + 1) % 3)], s2 = a[size_t((ia + 2) % 3)];
  const float size = max_component(abs(opposite - corner)) + max_component(abs(s2 - s1));
  if (!(max_component(abs((corner + opposite) - (s1 + s2))) <= kParallelogramTolerance * size)) return;
  quad_ = Parallelogram{corner, s1 - corner, s2 - corner, tris_[0].n};
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
  quad_.reset();  // the image is read at each triangle's own (u, v)
}

std::optional<LightSample> MeshLight::sample_li(const LightQuery& q, Vec2f u) const {
  if (!(total_area_ > 0.0f)) return std::nullopt;
  if (quad_) return connect(q, quad_->corner + quad_->side1 * u.x + quad_->side2 * u.y, quad_->n, 1.0f / total_area_,
                            radiance_);
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
  return connect(q, t.p0 * (1.0f - b.x - b.y) + t.p1 * b.x + t.p2 * b.y, t.n, pmf / t.area, radiance_at(i, b));
}

std::optional<LightSample> MeshLight::connect(const LightQuery& q, Vec3f p, Vec3f n, float area_pdf, Rgb li) const {
  const Vec3f to_light = p - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return std::nullopt;
  const float d = std::sqrt(d2);
  const Vec3f wi = to_light / d;
  const float cos_l = two_sided_ ? std::abs(dot(n, wi)) : -dot(n, wi);
  if (!(cos_l > 0.0f)) return std::nullopt;  // q sees the back (non-emitting) side, or the triangle edge-on
  LightSample s;
  s.li = li;
  s.wi = wi;
  s.p_light = p;
  s.n_light = n;
  s.distance = d;
  s.pdf = area_pdf * d2 / cos_l;
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
