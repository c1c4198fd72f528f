// pbrt-v4's "homogeneous" medium: constant coefficients everywhere inside the shapes that bound it (it has no box
// of its own; a camera or a light may sit in it).
//
// Parameters (already reduced by the loader, scenes/pbrt/media.cpp):
//   sigma_a, sigma_s  absorption and scattering per unit length ("sigma_a" / "sigma_s" or a "preset", times
//                     "scale")
//   le                emitted radiance ("Le" times "Lescale"); the medium emits sigma_a * le per unit length
//   g                 Henyey-Greenstein asymmetry
// Its majorant is its own extinction, so delta tracking never meets a null collision.
#pragma once
#include <string>

#include "materials/henyey_greenstein.h"
#include "media/majorant_grid.h"
#include "media/medium_properties.h"

namespace kiln {

class HomogeneousMedium {
 public:
  using Majorants = SingleMajorant;

  HomogeneousMedium(Rgb sigma_a, Rgb sigma_s, Rgb le, float g) : props_{sigma_a, sigma_s, le}, phase_{g} {}

  MediumProperties at(Vec3f) const { return props_; }
  Majorants majorants(const Ray&, float tmax) const {
    return SingleMajorant(MajorantSegment{0.0f, tmax, props_.sigma_a + props_.sigma_s});
  }
  const HenyeyGreenstein& phase() const { return phase_; }
  bool emissive() const { return !props_.le.is_black() && !props_.sigma_a.is_black(); }
  std::string describe() const;

 private:
  MediumProperties props_;
  HenyeyGreenstein phase_;
};

}  // namespace kiln
