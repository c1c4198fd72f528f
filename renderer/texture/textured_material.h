// Per-hit evaluation of pbrt-v4 materials whose parameters are textured, or that bend the shading normal
// (displacement, normal map). The material is built again at every hit from its parameters' values there
// (scenes/material_mapping.h build_pbrt_material: a function of the description and the evaluated parameters) into
// the integrator's scratch Material; materials without textures are built once with the world and cost nothing
// per hit.
#pragma once
#include <array>

#include "materials/material.h"
#include "renderer/texture/texture_graph.h"
#include "scenes/scene.h"

namespace kiln {

struct TexturedPbrtMaterial {
  PbrtMaterialDesc desc;             // its textured parameters' `value`s are filled per hit
  bool textured_parameters = false;  // else only the shading normal changes and the world's material is used
  bool needs_footprint = false;      // some texture it reads looks at the hit's footprint
};

// Whether d needs evaluation at hits (a textured parameter, a displacement or a normal map).
bool needs_per_hit_evaluation(const PbrtMaterialDesc& d);
// The record for d; compiles the textures it reads in g (opening their images: may throw kiln::Error).
TexturedPbrtMaterial make_textured_material(const PbrtMaterialDesc& d, TextureGraph& g);
// Two materials that between them have every lobe d can take at a hit (its textured floats all 0, all 1: smooth
// and rough), so that the world's feature mask covers what textures may choose.
std::array<Material, 2> per_hit_variants(const PbrtMaterialDesc& d);

}  // namespace kiln
