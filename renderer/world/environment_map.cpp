#include "renderer/world/environment_map.h"

#include <cmath>

#include "core/equal_area.h"
#include "core/error.h"
#include "renderer/image_io/image_io.h"

namespace kiln {
namespace {

Image read_map(const SceneDesc& scene, const EnvLightDesc& env) {
  try {
    Image img = read_image(env.image_path);
    if (img.width() <= 0 || img.height() <= 0) throw Error(env.image_path, "", "the image is empty");
    return img;
  } catch (const Error& e) {
    throw Error(scene.source_path, env.element, std::string("environment map: ") + e.what());
  }
}

// The layout and frame the image is read in.
EnvMapPlacement placement_of(const SceneDesc& scene, const EnvLightDesc& env, const Image& img,
                             std::vector<std::string>& warnings) {
  const auto size = [&] { return std::to_string(img.width()) + " x " + std::to_string(img.height()); };
  EnvMapFormat format = env.format;
  if (format == EnvMapFormat::EqualArea && img.width() != img.height()) {
    if (!env.lat_long_if_not_square || img.width() != 2 * img.height())
      throw Error(scene.source_path, env.element,
                  "environment map '" + env.image_path + "' is " + size() +
                      ": an equal-area map must be square (and a lat-long one 2:1)");
    warnings.push_back(Error::format(scene.source_path, env.element,
                                     "environment map '" + env.image_path + "' is " + size() +
                                         ", not square as pbrt-v4's equal-area maps are: read as a lat-long "
                                         "(equirectangular) map, z up, as pbrt-v3 did"));
    format = EnvMapFormat::LatLongZUp;
  }
  switch (format) {
    case EnvMapFormat::LatLongYUp: return {EnvMapLayout::LatLong, env.light_to_world};
    case EnvMapFormat::LatLongZUp: return {EnvMapLayout::LatLong, env.light_to_world * course_to_pbrt_lat_long()};
    case EnvMapFormat::EqualArea: return {EnvMapLayout::EqualArea, env.light_to_world};
  }
  return {};
}

}  // namespace

Transform course_to_pbrt_lat_long() {
  Mat4 c = Mat4::identity();
  c.m[0] = {0, 0, 1, 0};   // x' = z
  c.m[1] = {-1, 0, 0, 0};  // y' = -x
  c.m[2] = {0, 1, 0, 0};   // z' = y
  return Transform::from_matrix(c);
}

double pbrt_map_illuminance(const Image& image, EnvMapLayout layout) {
  const int w = image.width(), h = image.height();
  const double texels = double(w) * double(h);
  double k = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Vec2f uv((float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h));
      if (layout == EnvMapLayout::EqualArea) {
        const float cos_theta = equal_area_square_to_sphere(uv).z;
        if (cos_theta > 0.0f) k += double(image.at(x, y).luminance()) * cos_theta * (2.0 * kPi / texels);
      } else {  // the lat-long rows above the horizon: theta from the pole, half the texel's solid angle
        const double cos_theta = std::cos(kPi * double(uv.y));
        const double solid_angle =
            (2.0 * kPi / w) * (std::cos(kPi * double(y) / h) - std::cos(kPi * double(y + 1) / h));
        if (cos_theta > 0.0) k += double(image.at(x, y).luminance()) * cos_theta * 0.5 * solid_angle;
      }
    }
  }
  return k;
}

ImageInfiniteLight make_environment_light(const SceneDesc& scene, const EnvLightDesc& env, float scene_radius,
                                          EnvMapSampling sampling, std::vector<std::string>& warnings) {
  Image img = read_map(scene, env);
  const EnvMapPlacement placement = placement_of(scene, env, img, warnings);
  if (env.format != EnvMapFormat::LatLongYUp && !is_float_image_format(env.image_path))
    for (Rgb& c : img.pixels())
      for (int i = 0; i < 3; ++i) c[i] = srgb_to_linear(c[i]);
  float scale = env.scale;
  if (env.illuminance) {
    const double k = pbrt_map_illuminance(img, placement.layout);
    if (!(k > 0.0))
      throw Error(scene.source_path, env.element,
                  "\"illuminance\" cannot be met: the map is black above its horizon");
    scale *= float(double(*env.illuminance) / k);
  }
  if (scale != 1.0f)
    for (Rgb& c : img.pixels()) c *= scale;
  try {
    return ImageInfiniteLight(std::move(img), scene_radius, sampling, placement);
  } catch (const Error& e) {
    throw Error(scene.source_path, env.element, e.what());
  }
}

}  // namespace kiln
