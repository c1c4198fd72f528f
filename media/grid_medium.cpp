#include "media/grid_medium.h"

#include "media/describe_util.h"
#include "media/emission_table.h"

namespace kiln {

GridMedium::GridMedium(const Transform& medium_to_world, const Bounds3f& bounds, Rgb sigma_a, Rgb sigma_s, float g,
                       SampledGrid<float> density, GridEmission emission)
    : box_(medium_to_world, bounds),
      sigma_a_(sigma_a),
      sigma_s_(sigma_s),
      phase_{g},
      density_(std::move(density)),
      emission_(std::move(emission)),
      majorant_(majorant_resolution(density_.size(0), kGridMajorantResolution),
                majorant_resolution(density_.size(1), kGridMajorantResolution),
                majorant_resolution(density_.size(2), kGridMajorantResolution)) {
  majorant_.fill([&](const Bounds3f& region) { return density_.max_over(region, [](float d) { return d; }); });
}

MediumProperties GridMedium::at(Vec3f p) const {
  const Vec3f u = box_.unit_point(p);
  const float d = density_.lookup(u);
  MediumProperties mp{sigma_a_ * d, sigma_s_ * d, Rgb(0.0f)};
  if (!emission_.any()) return mp;
  const float s = emission_.le_scale.lookup(u);
  if (!(s > 0.0f)) return mp;
  if (emission_.temperature.empty()) {
    mp.le = emission_.le * s;
  } else {
    const float t = (emission_.temperature.lookup(u) - emission_.temperature_offset) * emission_.temperature_scale;
    mp.le = emission_at(emission_.blackbody, t) * s;
  }
  return mp;
}

GridMedium::Majorants GridMedium::majorants(const Ray& ray, float tmax) const {
  return box_.majorants(majorant_, ray, tmax, sigma_a_ + sigma_s_);
}

std::string GridMedium::describe() const {
  std::string d = "uniformgrid " + std::to_string(density_.size(0)) + "x" + std::to_string(density_.size(1)) + "x" +
                  std::to_string(density_.size(2)) + " sigma_a " + describe_rgb(sigma_a_) + " sigma_s " +
                  describe_rgb(sigma_s_) + " g " + describe_float(phase_.g) + ", majorant grid " + majorant_.describe();
  if (!emission_.temperature.empty()) d += ", temperature emission";
  else if (emission_.any()) d += ", Le " + describe_rgb(emission_.le);
  return d;
}

}  // namespace kiln
