#include "lights/light.h"

namespace kiln {

std::optional<LightSample> sample_li(const Light& light, const LightQuery& q, Vec2f u) {
  return std::visit([&](const auto& l) { return l.sample_li(q, u); }, light);
}

float pdf_li(const Light& light, const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) {
  return std::visit([&](const auto& l) { return l.pdf_li(q, p_light, n_light, prim); }, light);
}

std::optional<LightSample> sample_li(const Light& light, uint32_t part, const LightQuery& q, Vec2f u) {
  if (part == kWholeLight) return sample_li(light, q, u);
  const auto* mesh = std::get_if<MeshLight>(&light);
  return mesh ? mesh->sample_triangle_li(q, part, u) : std::nullopt;
}

float pdf_li(const Light& light, uint32_t part, const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) {
  if (part == kWholeLight) return pdf_li(light, q, p_light, n_light, prim);
  const auto* mesh = std::get_if<MeshLight>(&light);
  return mesh && part == prim ? mesh->pdf_triangle_li(q, p_light, part) : 0.0f;
}

Rgb emitted(const Light& light, Vec3f n, Vec3f w, const EmitterPoint& at) {
  return std::visit(
      [&](const auto& l) {
        if constexpr (requires { l.emitted(n, w, at); }) return l.emitted(n, w, at);
        else return l.emitted(n, w);
      },
      light);
}

float power(const Light& light) {
  return std::visit([](const auto& l) { return l.power(); }, light);
}

bool is_delta(const Light& light) {
  return std::visit([](const auto& l) { return std::decay_t<decltype(l)>::kDelta; }, light);
}

}  // namespace kiln
