// Light interface: every light type exposes sample_li / pdf_li / emitted (pbrt-v4 base/light.h style), behind one
// variant so the hot path has no virtual calls. LightQuery and LightSample live in lights/light_sample.h.
#pragma once
#include <cstdint>
#include <optional>
#include <variant>

#include "core/color.h"
#include "core/vec.h"
#include "lights/area_light.h"
#include "lights/directional_light.h"
#include "lights/image_infinite_light.h"
#include "lights/infinite_light.h"
#include "lights/light_sample.h"
#include "lights/mesh_light.h"
#include "lights/point_light.h"
#include "lights/quadric_light.h"
#include "lights/sphere_light.h"
#include "lights/spot_light.h"

namespace kiln {

using Light = std::variant<PointLight, SpotLight, DirectionalLight, AreaLight, MeshLight, SphereLight, InfiniteLight,
                           ImageInfiniteLight, QuadricLight>;

std::optional<LightSample> sample_li(const Light& light, const LightQuery& q, Vec2f u);
// Solid-angle pdf that sample_li would produce the point p_light (with surface normal n_light, on triangle
// prim for mesh lights) from q. 0 for point, spot and directional lights; the (never hit) AreaLight returns its
// real density.
float pdf_li(const Light& light, const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim);
// The part of a light a light sampler chooses (lights/light_sampler.h): the whole light, or one triangle of a mesh
// light (its index) when the sampler holds mesh lights triangle by triangle.
inline constexpr uint32_t kWholeLight = 0xffffffffu;
// sample_li / pdf_li for one part: kWholeLight is the light's own sampling; a triangle index samples that triangle of
// a mesh light alone (pdf_li is then the density given the triangle, and prim must be that triangle).
std::optional<LightSample> sample_li(const Light& light, uint32_t part, const LightQuery& q, Vec2f u);
float pdf_li(const Light& light, uint32_t part, const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim);
// Radiance leaving a point of an emitting surface with normal n towards direction w (w points away from it).
// n is the geometric normal as the shape defines it (mesh: winding order; sphere: outward), not face-forwarded.
// Mesh lights emit on the front side only, spheres outward only; lights that rays cannot hit return 0.
// at: where on the surface (lights with an emission image read it there; the others ignore it).
Rgb emitted(const Light& light, Vec3f n, Vec3f w, const EmitterPoint& at = {});
// Total emitted power (flux) estimate used by the power-proportional selector.
float power(const Light& light);
// True when rays can never hit the light (point, spot, directional and the invisible AreaLight): its samples
// carry LightSample::delta and must be added without MIS, and BSDF-sampled rays never find it.
bool is_delta(const Light& light);

}  // namespace kiln
