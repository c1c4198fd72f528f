#include "materials/mirror.h"

#include "materials/fresnel.h"

namespace kiln {

int Mirror::branches(Vec3f wo, SpecularBranch out[2]) const {
  if (wo.z == 0.0f || !is_finite(wo)) return 0;
  out[0] = SpecularBranch{reflect_z(wo), reflectance, 1.0f, false, 1.0f};
  return 1;
}

std::optional<BsdfSample> Mirror::sample(Vec3f wo, float uc, Vec2f /*u*/) const {
  SpecularBranch b[2];
  return sample_branch(b, branches(wo, b), uc);
}

std::optional<BsdfSample> sample_branch(const SpecularBranch* branches, int count, float uc) {
  if (count <= 0) return std::nullopt;
  int i = 0;
  float cdf = branches[0].probability;
  while (i + 1 < count && uc >= cdf) cdf += branches[++i].probability;
  const SpecularBranch& b = branches[i];
  const float cos_i = std::abs(b.wi.z);
  if (!(b.probability > 0.0f) || !(cos_i > 0.0f)) return std::nullopt;
  BsdfSample s;
  s.f = b.weight / cos_i;
  s.wi = b.wi;
  s.pdf = b.probability;
  s.flags = kLobeSpecular | (b.transmission ? kLobeTransmission : kLobeReflection);
  s.eta = b.transmission ? b.etap : 1.0f;
  if (!s.f.is_finite()) return std::nullopt;
  return s;
}

}  // namespace kiln
