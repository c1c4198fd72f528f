// A realistic camera's lens system, as pbrt-v4's "realistic" camera models it (the pbrt book, 4th ed., section 5.3):
// spherical glass interfaces and an aperture stop centred on the optical axis, traced exactly with Snell's law.
//
// Camera space: the film at z = 0, the lens towards +z; x to the image's right seen from behind the film, y up. The
// film's physical size is its diagonal (pbrt Film "diagonal") at the full film's aspect ratio; the lens inverts the
// image, so film point (x, y) shows the scene towards (-x, -y).
//
// Set-up, as pbrt does it: the film distance (the last interface's thickness) is moved so that the thick-lens
// approximation of the system (cardinal points from two rays parallel to the axis) focuses at focus_distance; then
// the exit pupil is bounded, for 64 rings of film radius, by tracing 2^20 film-to-rear-element rays per ring (a
// Halton point set over 1.5 times the rear element's radius) and growing a box over those that pass, expanded by
// two sample spacings. A camera ray samples the box of its ring (rotated to the film point's angle) uniformly and
// carries the weight cos^4(theta) / (pdf * d^2), d the rear element's distance from the film.
#pragma once
#include <string>
#include <vector>

#include "core/ray.h"
#include "scenes/scene.h"

namespace kiln {

struct PupilBounds {
  Vec2f lo{kInfinity, kInfinity}, hi{-kInfinity, -kInfinity};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y; }
  float area() const { return empty() ? 0.0f : (hi.x - lo.x) * (hi.y - lo.y); }
};

inline constexpr int kExitPupilRings = 64;
inline constexpr int kExitPupilSamples = 1 << 20;

class LensSystem {
 public:
  // full_width x full_height: the film's resolution (its aspect ratio); `where` names the camera in messages;
  // pupil_samples: rays per exit-pupil ring (pbrt's 2^20; fewer give looser bounds sooner).
  // Throws kiln::Error when the lens passes no ray or cannot focus at the requested distance.
  LensSystem(const LensSystemDesc& desc, int full_width, int full_height, const std::string& where,
             int pupil_samples = kExitPupilSamples);

  // The camera-space ray for the film position (fx, fy) in [0, 1]^2 of the full film (x right, y down) and lens
  // sample u; returns its weight, 0 when the lens blocks it.
  float generate(Vec2f film, Vec2f u, Ray& ray) const;

  // Traces a camera-space ray from the film side out of the front element (or from the scene side to the film);
  // 0 when an interface or the stop blocks it, 1 otherwise. out (when given) is the ray that leaves, in camera space.
  float trace_from_film(const Ray& r, Ray* out) const;
  float trace_from_scene(const Ray& r, Ray* out) const;

  float rear_z() const { return interfaces_.back().thickness; }
  float front_z() const;
  float film_diagonal() const { return diagonal_; }
  Vec2f film_size() const { return film_size_; }
  const std::vector<PupilBounds>& exit_pupil() const { return pupil_; }
  const std::vector<LensInterfaceDesc>& interfaces() const { return interfaces_; }

 private:
  void focus(float focus_distance, const std::string& where);
  PupilBounds bound_exit_pupil(float film_x0, float film_x1, uint32_t samples) const;

  std::vector<LensInterfaceDesc> interfaces_;
  float diagonal_ = 0.035f;
  Vec2f film_size_;
  std::vector<PupilBounds> pupil_;
};

}  // namespace kiln
