#include "renderer/texture/textured_material.h"

#include <type_traits>

#include "renderer/texture/bump_map.h"
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

}  // namespace kiln
