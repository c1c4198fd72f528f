#include "renderer/texture/textured_material.h"

#include <type_traits>

#include "renderer/texture/bump_map.h"
#include "renderer/world/interaction.h"
#include "scenes/material_mapping.h"

namespace kiln {

bool needs_per_hit_evaluation(const PbrtMaterialDesc& d) {
  bool textured = d.displacement >= 0 || d.normal_map >= 0;
  for_each_texturable(d, [&](const auto& p) { textured = textured || p.textured(); });
  return textured;
}

TexturedPbrtMaterial make_textured_material(const PbrtMaterialDesc& d, TextureGraph& g) {
  TexturedPbrtMaterial m;
  m.desc = d;
  const auto use = [&](int texture) {
    g.use(texture);
    m.needs_footprint = m.needs_footprint || g.needs_footprint(texture);
  };
  for_each_texturable(d, [&](const auto& p) {
    if (!p.textured()) return;
    use(p.texture);
    m.textured_parameters = true;
  });
  if (d.normal_map >= 0) {
    g.use(d.normal_map);  // read at the finest level: no footprint
  } else if (d.displacement >= 0) {
    use(d.displacement);
    m.needs_footprint = true;  // the difference steps are half a footprint
  }
  return m;
}

std::array<Material, 2> per_hit_variants(const PbrtMaterialDesc& d) {
  std::array<Material, 2> out;
  for (int i = 0; i < 2; ++i) {
    PbrtMaterialDesc v = d;
    for_each_texturable(v, [&](auto& p) {
      if constexpr (std::is_same_v<std::decay_t<decltype(p)>, TexturedFloat>)
        if (p.textured()) p.value = float(i);
    });
    out[size_t(i)] = build_pbrt_material(v);
  }
  return out;
}

void resolve_textured_material(const TextureGraph& g, const TexturedPbrtMaterial& m, const TextureEvalContext& c,
                               bool smooth, SurfaceInteraction& si, Material& scratch) {
  const PbrtMaterialDesc& d = m.desc;
  if (d.normal_map >= 0 || d.displacement >= 0) {
    Vec3f dpdu = si.dpdu, dpdv = si.dpdv;
    if (smooth) shading_tangents(si.ns, si.dpdu, dpdu, dpdv);
    const Vec3f n = d.normal_map >= 0 ? normal_mapped_normal(g, d.normal_map, c, si.ns, dpdu)
                                      : bump_mapped_normal(g, d.displacement, c, si.ns, dpdu, dpdv);
    si.ns = unit_on_side(n, si.ng);
  }
  if (!m.textured_parameters) return;
  PbrtMaterialDesc evaluated = d;
  for_each_texturable(evaluated, [&](auto& p) {
    if (!p.textured()) return;
    if constexpr (std::is_same_v<std::decay_t<decltype(p)>, TexturedFloat>)
      p.value = g.eval_float(p.texture, c);
    else
      p.value = g.eval_rgb(p.texture, c);
  });
  scratch = build_pbrt_material(evaluated);
  si.material = &scratch;
}

}  // namespace kiln
