#include "renderer/integrators/aov.h"

#include <sstream>

#include "core/error.h"

namespace kiln {

// Albedo as denoisers expect it: the material's reflectance colour (diffuse + specular for the course BRDFs, the
// mirror colour for delta materials, white for glass; pbrt's rough conductor: its normal-incidence Fresnel colour,
// coated diffuse: its base colour, coated conductor: the conductor's normal-incidence colour under the coat,
// diffuse transmission: reflectance plus transmittance).
Rgb material_albedo(const Material& m) {
  const Rgb surface = std::visit(
      [](const auto& b) -> Rgb {
        using T = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<T, NoSurface>) return Rgb(0.0f);
        else if constexpr (std::is_same_v<T, Lambert>) return b.reflectance;
        else if constexpr (std::is_same_v<T, RoughConductor>) return fresnel_conductor(1.0f, b.ior);
        else if constexpr (std::is_same_v<T, RoughDielectric>) return Rgb(1.0f);
        else if constexpr (std::is_same_v<T, CoatedDiffuse>) return b.base.reflectance;
        else if constexpr (std::is_same_v<T, CoatedConductor>) return fresnel_conductor(1.0f, b.base.ior);
        else if constexpr (std::is_same_v<T, DiffuseTransmission>) return b.reflectance + b.transmittance;
        else return b.kd + b.ks;
      },
      m.surface);
  const Rgb delta = std::visit(
      [](const auto& d) -> Rgb {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, NoDelta>) return Rgb(0.0f);
        else if constexpr (std::is_same_v<T, Dielectric> || std::is_same_v<T, ThinDielectric>) return Rgb(1.0f);
        else return d.reflectance;
      },
      m.delta);
  const Rgb a = surface + delta;
  return Rgb(std::min(a.r, 1.0f), std::min(a.g, 1.0f), std::min(a.b, 1.0f));
}

uint32_t parse_aovs(const std::string& list) {
  uint32_t flags = 0;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ',')) {
    if (name == "albedo") flags |= kAovAlbedo;
    else if (name == "normal") flags |= kAovNormal;
    else if (name == "depth") flags |= kAovDepth;
    else if (name == "position") flags |= kAovPosition;
    else if (name == "variance") flags |= kAovVariance;
    else if (name == "all") flags |= kAovAlbedo | kAovNormal | kAovDepth | kAovPosition | kAovVariance;
    else throw Error("--aov", "", "unknown AOV '" + name + "' (albedo, normal, depth, position, variance, all)");
  }
  return flags;
}

namespace {

// One layer of `channels` values per pixel, each pixel's from value(x, y, out).
template <typename Value>
AovLayer film_layer(const Film& film, std::vector<std::string> channels, Value&& value) {
  const size_t n = channels.size();
  AovLayer layer{std::move(channels), std::vector<float>(size_t(film.width()) * size_t(film.height()) * n)};
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) value(x, y, &layer.data[(size_t(y) * size_t(film.width()) + size_t(x)) * n]);
  return layer;
}

void put(float* out, Vec3f v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

}  // namespace

std::vector<AovLayer> aov_layers(const Film& film, uint32_t flags) {
  std::vector<AovLayer> layers;
  if (flags & kAovAlbedo)
    layers.push_back(film_layer(film, {"Albedo.R", "Albedo.G", "Albedo.B"}, [&](int x, int y, float* out) {
      const Rgb a = film.surface_mean(x, y).albedo;
      put(out, Vec3f{a.r, a.g, a.b});
    }));
  if (flags & kAovNormal)
    layers.push_back(film_layer(film, {"N.X", "N.Y", "N.Z"},
                                [&](int x, int y, float* out) { put(out, film.surface_mean(x, y).n); }));
  if (flags & kAovDepth)
    layers.push_back(film_layer(film, {"Z"}, [&](int x, int y, float* out) { *out = film.surface_mean(x, y).z; }));
  if (flags & kAovPosition)
    layers.push_back(film_layer(film, {"P.X", "P.Y", "P.Z"},
                                [&](int x, int y, float* out) { put(out, film.surface_mean(x, y).p); }));
  if (flags & kAovVariance) {
    const Image v = film.variance_of_mean();
    layers.push_back(film_layer(film, {"Variance.R", "Variance.G", "Variance.B"}, [&](int x, int y, float* out) {
      const Rgb c = v.at(x, y);
      put(out, Vec3f{c.r, c.g, c.b});
    }));
  }
  return layers;
}

}  // namespace kiln
