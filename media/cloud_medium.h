// pbrt-v4's procedural "cloud" medium: a density in [0, 1] made of octaves of Perlin noise (core/perlin.h) over the
// box [p0, p1] of the medium's space, scaling constant coefficients: sigma_a(p) = d(p) sigma_a, sigma_s(p) =
// d(p) sigma_s. At a point p of the medium's space (y up):
//   * the noise is looked up at q = frequency p, first pushed along the noise's gradient by two octaves of
//     "wispiness" (amplitudes 0.05 w and 0.025 w at frequencies 10 and 19.9), which draws wisps out of the edges;
//   * five octaves of noise at q (amplitudes 1/2, 1/4, ..., frequencies 1.99^i) sum to n;
//   * d = clamp(clamp(4.5 density (1 - p.y) n, 0, 1) + 2 max(0, 1/2 - p.y), 0, 1): thinner with height, and solid
//     at its base (d = 1 wherever p.y <= 0);
//   * d = 0 outside [p0, p1].
// Kiln's noise has its own permutation: the cloud has pbrt's kind of shape, not pbrt's exact pattern.
//
// Parameters (scenes/pbrt/media.cpp):
//   sigma_a, sigma_s    per unit length at density 1 (times "scale")
//   g                   Henyey-Greenstein asymmetry
//   shape               "density" (1), "wispiness" (1), "frequency" (5), as pbrt-v4 names them
// The majorant is sigma_a + sigma_s (d <= 1) over the part of a ray inside the box, as pbrt-v4's.
#pragma once
#include <string>

#include "materials/henyey_greenstein.h"
#include "media/majorant_grid.h"
#include "media/medium_properties.h"

namespace kiln {

struct CloudShape {
  float density = 1.0f;    // how quickly the noise saturates to a solid cloud
  float wispiness = 1.0f;  // how far the edges are drawn out; 0 keeps the plain noise
  float frequency = 5.0f;  // noise cells per unit of the medium's space
};

class CloudMedium {
 public:
  using Majorants = SingleMajorant;

  CloudMedium(const Transform& medium_to_world, const Bounds3f& bounds, Rgb sigma_a, Rgb sigma_s, float g,
              CloudShape shape);

  MediumProperties at(Vec3f p) const;
  Majorants majorants(const Ray& ray, float tmax) const;
  const HenyeyGreenstein& phase() const { return phase_; }
  bool emissive() const { return false; }
  std::string describe() const;

  // d at a point of the medium's own space (the header's definition), in [0, 1].
  float density(Vec3f p_medium) const;

 private:
  MediumBox box_;
  Transform world_to_medium_;
  Rgb sigma_a_, sigma_s_;
  HenyeyGreenstein phase_;
  CloudShape shape_;
};

}  // namespace kiln
