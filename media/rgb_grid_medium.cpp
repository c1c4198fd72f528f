#include "media/rgb_grid_medium.h"

#include "media/describe_util.h"

namespace kiln {
namespace {

// Lattice dimensions of the first non-empty grid.
int lattice_size(const SampledGrid<Rgb>& a, const SampledGrid<Rgb>& b, int axis) {
  return a.empty() ? b.size(axis) : a.size(axis);
}

}  // namespace

RgbGridMedium::RgbGridMedium(const Transform& medium_to_world, const Bounds3f& bounds, SampledGrid<Rgb> sigma_a,
                             SampledGrid<Rgb> sigma_s, float scale, SampledGrid<Rgb> le, float le_scale, float g)
    : box_(medium_to_world, bounds),
      sigma_a_(std::move(sigma_a)),
      sigma_s_(std::move(sigma_s)),
      le_(std::move(le)),
      scale_(scale),
      le_scale_(le_scale),
      phase_{g},
      majorant_(majorant_resolution(lattice_size(sigma_a_, sigma_s_, 0), kGridMajorantResolution),
                majorant_resolution(lattice_size(sigma_a_, sigma_s_, 1), kGridMajorantResolution),
                majorant_resolution(lattice_size(sigma_a_, sigma_s_, 2), kGridMajorantResolution)) {
  // An absent lattice is 1 everywhere. max_over of a channel maximum bounds every channel of the interpolation.
  const auto max_of = [](const SampledGrid<Rgb>& lattice, const Bounds3f& r) {
    return lattice.empty() ? 1.0f : lattice.max_over(r, [](Rgb c) { return c.max_component(); });
  };
  majorant_.fill([&](const Bounds3f& r) { return scale_ * (max_of(sigma_a_, r) + max_of(sigma_s_, r)); });
}

MediumProperties RgbGridMedium::at(Vec3f p) const {
  const Vec3f u = box_.unit_point(p);
  MediumProperties mp;
  mp.sigma_a = (sigma_a_.empty() ? Rgb(1.0f) : sigma_a_.lookup(u)) * scale_;
  mp.sigma_s = (sigma_s_.empty() ? Rgb(1.0f) : sigma_s_.lookup(u)) * scale_;
  if (!le_.empty()) mp.le = le_.lookup(u) * le_scale_;
  return mp;
}

RgbGridMedium::Majorants RgbGridMedium::majorants(const Ray& ray, float tmax) const {
  return box_.majorants(majorant_, ray, tmax, Rgb(1.0f));
}

std::string RgbGridMedium::describe() const {
  return "rgbgrid " + std::to_string(lattice_size(sigma_a_, sigma_s_, 0)) + "x" +
         std::to_string(lattice_size(sigma_a_, sigma_s_, 1)) + "x" + std::to_string(lattice_size(sigma_a_, sigma_s_, 2)) +
         " scale " + describe_float(scale_) + " g " + describe_float(phase_.g) + (emissive() ? ", Le lattice" : "");
}

}  // namespace kiln
