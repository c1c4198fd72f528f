// Emissive triangle mesh (CENG795 LightMesh): one light over all of its triangles.
//   positions  WORLD-space vertex positions (the loader applies the mesh's transformations)
//   indices    0-based vertex index triplets; triangle i is indices[3i..3i+2] and is the `prim` the accelerator
//              reports for that triangle
//   radiance   constant radiance L emitted from the FRONT side only: the side of the geometric normal
//              (v1 - v0) x (v2 - v0) (right-hand rule, spec sections 7 and 9)
//   two_sided  emit L from both sides instead (pbrt's "twosided" area lights)
//   image      instead of L, an image over the triangles' (u, v) (lights/emission_image.h): tri_uvs holds each
//              triangle's corners' (u, v); radiance() and power() then take the image's mean
// A sample picks a triangle with probability proportional to its area (zero-area triangles are never picked),
// then a uniform point on it; the area pdf 1/A_total becomes the solid-angle pdf d^2 / (|cos theta_l| A_total).
// Two triangles that make one parallelogram facing one way (a quad lamp) are sampled as that parallelogram, a
// corner plus u.x and u.y times its sides: the same uniform density, without choosing a triangle or warping a
// square onto one (a tenth of a diffuse room's render time went into sample_li).
#pragma once
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "core/sampling.h"
#include "lights/emission_image.h"
#include "lights/light_sample.h"

namespace kiln {

class MeshLight {
 public:
  // Throws kiln::Error when indices is not a multiple of 3 or names a vertex that does not exist.
  MeshLight(std::span<const Vec3f> positions, std::span<const uint32_t> indices, Rgb radiance,
            bool two_sided = false);
  MeshLight(std::span<const Vec3f> positions, std::span<const uint32_t> indices,
            std::shared_ptr<const EmissionImage> image, std::vector<std::array<Vec2f, 3>> tri_uvs,
            bool two_sided = false);

  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  // Density of sample_li at p_light on triangle prim; 0 when q is behind that triangle's emitting side.
  float pdf_li(const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) const;
  // The same for triangle i alone (a light hierarchy chose it): a uniform point on it, pdf d^2 / (|cos| A_i).
  std::optional<LightSample> sample_triangle_li(const LightQuery& q, size_t i, Vec2f u) const;
  float pdf_triangle_li(const LightQuery& q, Vec3f p_light, size_t i) const;
  // n must be the triangle's geometric normal in winding order (not face-forwarded); at: the hit's triangle and
  // barycentrics.
  Rgb emitted(Vec3f n, Vec3f w, const EmitterPoint& at = {}) const {
    const float c = dot(n, w);
    if (!(c > 0.0f || (two_sided_ && c < 0.0f))) return Rgb{};
    return image_ ? radiance_at(at.prim, at.hit_uv) : radiance_;
  }
  float power() const { return (two_sided_ ? 2.0f : 1.0f) * kPi * total_area_ * radiance_.luminance(); }
  bool two_sided() const { return two_sided_; }
  static constexpr bool kDelta = false;

  size_t triangle_count() const { return tris_.size(); }
  float total_area() const { return total_area_; }
  float triangle_area(size_t i) const { return tris_[i].area; }
  // Probability that a sample lands on triangle i.
  float triangle_pmf(size_t i) const { return dist_.pmf(i); }
  // Triangle i's corners and unit geometric normal (zero when degenerate).
  std::array<Vec3f, 3> triangle(size_t i) const { return {tris_[i].p0, tris_[i].p1, tris_[i].p2}; }
  Vec3f triangle_normal(size_t i) const { return tris_[i].n; }
  // The constant radiance, or an emission image's mean.
  Rgb radiance() const { return radiance_; }
  bool has_image() const { return image_ != nullptr; }

 private:
  struct Tri;
  // A uniform point on triangle i (barycentric sample u) seen from q, with solid-angle pdf (pmf / area) d^2 / cos.
  std::optional<LightSample> sample_on(const LightQuery& q, size_t i, float pmf, Vec2f u) const;
  // Radiance at barycentrics b of triangle i (b.x, b.y: the weights of its second and third corners).
  Rgb radiance_at(size_t i, Vec2f b) const {
    if (!image_ || i >= tri_uvs_.size()) return radiance_;
    const std::array<Vec2f, 3>& t = tri_uvs_[i];
    return image_->radiance(t[0] * (1.0f - b.x - b.y) + t[1] * b.x + t[2] * b.y);
  }
  float pdf_on(const LightQuery& q, Vec3f p_light, const Tri& t, float pmf) const;
  // The point p_light with normal n on the emitter, seen from q, with area density area_pdf.
  std::optional<LightSample> connect(const LightQuery& q, Vec3f p_light, Vec3f n, float area_pdf, Rgb li) const;
  void find_parallelogram();

  // corner + u.x side1 + u.y side2 covers both triangles (find_parallelogram).
  struct Parallelogram {
    Vec3f corner, side1, side2, n;
  };

  struct Tri {
    Vec3f p0, p1, p2;
    Vec3f n;  // unit geometric normal; zero for degenerate triangles
    float area = 0;
  };
  std::vector<Tri> tris_;
  std::optional<Parallelogram> quad_;  // constant radiance only
  Distribution1D dist_;
  Rgb radiance_;
  float total_area_ = 0;
  bool two_sided_ = false;
  std::shared_ptr<const EmissionImage> image_;  // null: radiance_ everywhere
  std::vector<std::array<Vec2f, 3>> tri_uvs_;   // with image_ only
};

}  // namespace kiln
