#include "renderer/world/features.h"

#include <utility>

namespace kiln {

std::string describe_features(uint32_t mask) {
  static const std::pair<Feature, const char*> kNames[] = {
      {kFeatureTriangles, "triangles"},     {kFeatureSpheres, "spheres"},
      {kFeatureInstances, "instances"},     {kFeatureSmoothNormals, "smooth-normals"},
      {kFeaturePointLights, "point-lights"}, {kFeatureAreaLights, "area-lights"},
      {kFeatureMeshLights, "mesh-lights"},  {kFeatureSphereLights, "sphere-lights"},
      {kFeatureAmbient, "ambient"},         {kFeatureGlossy, "glossy"},
      {kFeatureDelta, "delta"},             {kFeatureDielectric, "dielectric"},
      {kFeatureTextures, "textures"},       {kFeatureDepthOfField, "depth-of-field"},
      {kFeatureInfiniteLights, "infinite-lights"}, {kFeatureMotionBlur, "motion-blur"},
      {kFeatureEnvironmentMap, "environment-map"},  {kFeatureBackfaceCulling, "backface-culling"},
      {kFeatureQuadrics, "quadrics"},       {kFeatureQuadricLights, "quadric-lights"},
      {kFeatureAlpha, "alpha"},
      {kFeatureMix, "mix"},
      {kFeatureMedia, "media"},
  };
  std::string s;
  for (const auto& [bit, name] : kNames)
    if (mask & bit) {
      if (!s.empty()) s.push_back(',');
      s.append(name);
    }
  return s.empty() ? "none" : s;
}

}  // namespace kiln
