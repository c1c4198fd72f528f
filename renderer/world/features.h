// Per-scene feature mask (Cycles kernel/features.h style): what the scene contains, so that only those parts
// are built and the integrator can skip the code paths the scene lacks.
#pragma once
#include <cstdint>
#include <string>

namespace kiln {

enum Feature : uint32_t {
  kFeatureTriangles = 1u << 0,
  kFeatureSpheres = 1u << 1,
  kFeatureInstances = 1u << 2,
  kFeatureSmoothNormals = 1u << 3,
  kFeaturePointLights = 1u << 4,      // point, spot and directional (delta) lights
  kFeatureAreaLights = 1u << 5,       // course square AreaLight
  kFeatureMeshLights = 1u << 6,
  kFeatureSphereLights = 1u << 7,
  kFeatureAmbient = 1u << 8,
  kFeatureGlossy = 1u << 9,           // Phong / Blinn-Phong / Torrance-Sparrow lobes
  kFeatureDelta = 1u << 10,           // mirror / dielectric / conductor
  kFeatureDielectric = 1u << 11,     // oriented materials (smooth or rough dielectrics): media are tracked
  kFeatureTextures = 1u << 12,        // image or procedural textures (SceneTextures built)
  kFeatureDepthOfField = 1u << 13,
  kFeatureInfiniteLights = 1u << 14,  // rays that leave the scene see light
  kFeatureMotionBlur = 1u << 15,      // moving shapes or camera: rays take a time sample, accelerators vary in time
  kFeatureEnvironmentMap = 1u << 16,  // an image-based infinite light (lat-long environment map)
  kFeatureBackfaceCulling = 1u << 17, // camera rays skip triangles facing away from them (course rules)
  kFeatureQuadrics = 1u << 18,        // pbrt disks, cylinders and partial spheres (user geometry)
  kFeatureQuadricLights = 1u << 19,   // emitting quadrics
  kFeatureAlpha = 1u << 20,           // alpha cut-outs: the accelerators test shapes' opacity at candidate hits
  kFeatureMix = 1u << 21,             // mix materials: each hit chooses one of a mix's components (World::mixes)
  kFeatureMedia = 1u << 22,           // participating media: the volumetric path tracer renders the scene
  kFeatureAll = 0xffffffffu,
};

std::string describe_features(uint32_t mask);

// The integrators' specialisation on a scene's mask: calls f.template operator()<kDelta, kDielectric, kMeshesOnly>()
// (f a lambda with a template parameter list), so that f instantiates its kernel for the parts the scene has.
// Dielectrics imply delta lobes (smooth interfaces); "meshes only" means no sphere, quadric, instance or moving-shape
// dispatch.
template <class F>
decltype(auto) dispatch_on_features(uint32_t features, F&& f) {
  const bool delta = features & kFeatureDelta, dielectric = features & kFeatureDielectric;
  if (!(features & (kFeatureSpheres | kFeatureQuadrics | kFeatureInstances | kFeatureMotionBlur))) {
    if (dielectric) return f.template operator()<true, true, true>();
    if (delta) return f.template operator()<true, false, true>();
    return f.template operator()<false, false, true>();
  }
  if (dielectric) return f.template operator()<true, true, false>();
  if (delta) return f.template operator()<true, false, false>();
  return f.template operator()<false, false, false>();
}

}  // namespace kiln
