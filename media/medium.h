// A participating medium (pbrt-v4 media.h): one of the medium classes behind a variant, so the tracking loop is
// instantiated per class (media/tracking.h) with no virtual calls. Each class provides
//   MediumProperties at(Vec3f p)               coefficients and emission at a world-space point
//   Majorants majorants(const Ray&, float tmax) its majorant segments along a ray (unit direction)
//   const HenyeyGreenstein& phase()            its phase function
//   bool emissive(), std::string describe()
// and documents its parameters at the top of its header.
#pragma once
#include <string>
#include <variant>

#include "media/cloud_medium.h"
#include "media/grid_medium.h"
#include "media/homogeneous_medium.h"
#include "media/nanovdb_medium.h"
#include "media/rgb_grid_medium.h"

namespace kiln {

using Medium = std::variant<HomogeneousMedium, GridMedium, RgbGridMedium, NanoVdbMedium, CloudMedium>;

// The media on the two sides of a surface (pbrt-v4's MediumInterface): indices into the world's media, -1 for
// vacuum. A surface whose two sides hold the same medium is no transition: rays keep the medium they are in.
struct MediumInterface {
  int inside = -1, outside = -1;
  bool transition() const { return inside != outside; }
  // The medium a ray leaving the surface along w enters; ng is the surface's outward geometric normal.
  int entered(Vec3f w, Vec3f ng) const { return dot(w, ng) > 0.0f ? outside : inside; }
};

inline MediumProperties medium_at(const Medium& m, Vec3f p) {
  return std::visit([&](const auto& x) { return x.at(p); }, m);
}
inline const HenyeyGreenstein& medium_phase(const Medium& m) {
  return std::visit([](const auto& x) -> const HenyeyGreenstein& { return x.phase(); }, m);
}
inline bool medium_emissive(const Medium& m) {
  return std::visit([](const auto& x) { return x.emissive(); }, m);
}
inline std::string describe_medium(const Medium& m) {
  return std::visit([](const auto& x) { return x.describe(); }, m);
}

}  // namespace kiln
