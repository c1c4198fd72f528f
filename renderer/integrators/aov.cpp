#include "renderer/integrators/aov.h"

#include <tbb/parallel_for.h>

#include <sstream>

#include "core/error.h"
#include "renderer/world/interaction.h"

namespace kiln {
namespace {

// Albedo as denoisers expect it: the material's reflectance colour (diffuse + specular for the course BRDFs, the
// mirror colour for delta materials, white for glass; pbrt's rough conductor: its normal-incidence Fresnel colour,
// coated diffuse: its base colour).
Rgb material_albedo(const Material& m) {
  const Rgb surface = std::visit(
      [](const auto& b) -> Rgb {
        using T = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<T, NoSurface>) return Rgb(0.0f);
        else if constexpr (std::is_same_v<T, Lambert>) return b.reflectance;
        else if constexpr (std::is_same_v<T, RoughConductor>) return fresnel_conductor(1.0f, b.ior);
        else if constexpr (std::is_same_v<T, RoughDielectric>) return Rgb(1.0f);
        else if constexpr (std::is_same_v<T, CoatedDiffuse>) return b.reflectance;
        else return b.kd + b.ks;
      },
      m.surface);
  const Rgb delta = std::visit(
      [](const auto& d) -> Rgb {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, NoDelta>) return Rgb(0.0f);
        else if constexpr (std::is_same_v<T, Dielectric>) return Rgb(1.0f);
        else return d.reflectance;
      },
      m.delta);
  const Rgb a = surface + delta;
  return Rgb(std::min(a.r, 1.0f), std::min(a.g, 1.0f), std::min(a.b, 1.0f));
}

}  // namespace

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

std::vector<AovLayer> render_aovs(const World& world, const Camera& camera, uint32_t flags, const Film& film,
                                  const RenderOptions& options, uint32_t samples) {
  const int w = camera.width(), h = camera.height();
  const size_t npx = size_t(w) * size_t(h);
  std::vector<float> albedo(npx * 3, 0.0f), normal(npx * 3, 0.0f), depth(npx, 0.0f), position(npx * 3, 0.0f);
  const bool geometric = flags & (kAovAlbedo | kAovNormal | kAovDepth | kAovPosition);
  const uint32_t n = std::max(1u, samples);
  const uint32_t grid = std::max(1u, uint32_t(std::sqrt(double(n))));
  if (geometric) {
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
      for (int y = rows.begin(); y != rows.end(); ++y)
        for (int x = 0; x < w; ++x) {
          const size_t i = size_t(y) * size_t(w) + size_t(x);
          Rgb a(0.0f);
          Vec3f nn(0.0f), pp(0.0f);
          float z = 0.0f;
          uint32_t hits = 0;
          for (uint32_t s = 0; s < grid * grid; ++s) {
            // The AOV pass has its own stream (sample indices past any beauty sample) so it never perturbs the image.
            Rng rng = pixel_sample_rng(options.seed ^ 0xa0fu, uint32_t(x), uint32_t(y), s);
            const Vec2f j = rng.next_2d();
            const Vec2f lens = rng.next_2d();
            // Moving shapes and cameras averaged over the shutter.
            const float time = (world.features & kFeatureMotionBlur) ? rng.next_float() : 0.0f;
            const CameraRay cr = camera.sample(float(x) + (float(s % grid) + j.x) / float(grid),
                                               float(y) + (float(s / grid) + j.y) / float(grid), lens, time);
            if (!(cr.weight > 0.0f)) continue;
            const Ray& ray = cr.ray;
            Hit hit;
            if (!world.accel->intersect(ray, hit)) continue;
            SurfaceInteraction si = make_interaction(world, ray, hit);
            if (dot(si.ns, ray.d) > 0.0f) si.ns = -si.ns;  // face the camera, as denoisers expect
            a += si.material ? material_albedo(*si.material) : Rgb(1.0f);
            nn += si.ns;
            pp += si.p;
            z += hit.t * length(ray.d);
            ++hits;
          }
          if (hits == 0) continue;
          const float inv = 1.0f / float(grid * grid);
          const float invh = 1.0f / float(hits);
          for (int c = 0; c < 3; ++c) {
            albedo[3 * i + size_t(c)] = a[c] * inv;
            normal[3 * i + size_t(c)] = nn[c] * inv;
            position[3 * i + size_t(c)] = pp[c] * invh;
          }
          depth[i] = z * invh;
        }
    });
  }
  std::vector<AovLayer> layers;
  if (flags & kAovAlbedo) layers.push_back({{"Albedo.R", "Albedo.G", "Albedo.B"}, std::move(albedo)});
  if (flags & kAovNormal) layers.push_back({{"N.X", "N.Y", "N.Z"}, std::move(normal)});
  if (flags & kAovDepth) layers.push_back({{"Z"}, std::move(depth)});
  if (flags & kAovPosition) layers.push_back({{"P.X", "P.Y", "P.Z"}, std::move(position)});
  if (flags & kAovVariance) {
    const Image v = film.variance_of_mean();
    std::vector<float> data(npx * 3);
    for (size_t i = 0; i < npx; ++i)
      for (int c = 0; c < 3; ++c) data[3 * i + size_t(c)] = v.pixels()[i][c];
    layers.push_back({{"Variance.R", "Variance.G", "Variance.B"}, std::move(data)});
  }
  return layers;
}

}  // namespace kiln
