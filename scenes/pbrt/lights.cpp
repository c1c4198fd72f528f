// pbrt-v4 LightSource and AreaLightSource directives into the SceneDesc's lights.
#include "scenes/pbrt/builder.h"

#include <cmath>

#include "core/error.h"

namespace kiln {

Rgb PbrtBuilder::light_spectrum(const PbrtParams& ps, const std::string& name) {
  if (ps.find_texture(name)) ps.fail(ps.line(), in_quotes(name) + " of a light cannot be a texture");
  return ps.find_spectrum(name, SpectrumUse::Illuminant).value_or(Rgb(1.0f));
}

void PbrtBuilder::make_light(const std::string& type, const PbrtParams& ps, const Transform& xf) {
  const float scale = ps.get_float("scale", 1.0f);
  if (type == "point") {
    float s = scale;
    if (const float power = ps.get_float("power", -1.0f); power > 0.0f) s *= power / (4.0f * kPi);
    const Rgb i = light_spectrum(ps, "I") * s;
    scene_.point_lights.push_back({xf.point(ps.find_point3("from").value_or(Vec3f(0.0f))), i});
  } else if (type == "spot") {
    const float cone = ps.get_float("coneangle", kPbrtDefaultSpotConeAngle);
    const float delta = ps.get_float("conedeltaangle", kPbrtDefaultSpotConeDelta);
    if (!(cone > 0.0f) || cone > 180.0f || delta < 0.0f)
      ps.fail(ps.line(), "\"coneangle\" must lie in (0, 180] and \"conedeltaangle\" must not be negative");
    const float inner = std::max(0.0f, cone - delta);
    float s = scale;
    if (const float power = ps.get_float("power", -1.0f); power > 0.0f) {
      const float cos_end = std::cos(radians(cone)), cos_start = std::cos(radians(inner));
      s *= power / (2.0f * kPi * ((1.0f - cos_start) + 0.5f * (cos_start - cos_end)));
    }
    const Vec3f from = ps.find_point3("from").value_or(Vec3f(0.0f));
    const Vec3f to = ps.find_point3("to").value_or(Vec3f(0, 0, 1));
    const Vec3f dir = xf.vector(to - from);
    if (!(length(dir) > 0.0f) || !is_finite(dir)) ps.fail(ps.line(), "\"from\" and \"to\" must differ");
    SpotLightDesc l;
    l.position = xf.point(from);
    l.direction = normalize(dir);
    l.intensity = light_spectrum(ps, "I") * s;
    l.coverage_deg = 2.0f * cone;
    l.falloff_deg = 2.0f * inner;
    l.falloff = SpotFalloff::SmoothStep;
    scene_.spot_lights.push_back(l);
  } else if (type == "distant") {
    float s = scale;
    if (const float e = ps.get_float("illuminance", -1.0f); e > 0.0f) s *= e;
    const Vec3f from = ps.find_point3("from").value_or(Vec3f(0.0f));
    const Vec3f to = ps.find_point3("to").value_or(Vec3f(0, 0, 1));
    const Vec3f dir = xf.vector(to - from);
    if (!(length(dir) > 0.0f) || !is_finite(dir)) ps.fail(ps.line(), "\"from\" and \"to\" must differ");
    scene_.directional_lights.push_back({normalize(dir), light_spectrum(ps, "L") * s});
  } else if (type == "infinite") {
    infinite_light(ps, scale, xf);
  } else {
    diag_.warn(ps, "light " + in_quotes(type) + " is not supported; skipped");
    diag_.unsupported("pbrt light " + in_quotes(type), LoadOutcome::Ignored);
    for (const PbrtParam& p : ps.params()) p.used = true;
  }
  diag_.report_unused(ps);
}

void PbrtBuilder::infinite_light(const PbrtParams& ps, float scale, const Transform& light_to_world) {
  const auto file = ps.find_string("filename");
  if (file && ps.has("L")) ps.fail(ps.line(), "cannot have both \"L\" and \"filename\" (pbrt-v4 refuses it too)");
  if (ps.has("portal")) {
    ps.get_point3s("portal");
    diag_.warn(ps, "\"portal\" is ignored: the light is sampled over the whole sphere (unbiased, only noisier)");
  }
  if (file) return image_infinite_light(ps, *file, scale, light_to_world);
  float s = scale;
  if (const float e = ps.get_float("illuminance", -1.0f); e > 0.0f) s *= e / kPi;
  scene_.infinite_lights.push_back({light_spectrum(ps, "L") * s});
}

// pbrt-v4's ImageInfiniteLight: an equal-area square map in the light's frame; non-square 2:1 maps are read as
// pbrt-v3's lat-long (renderer/world/environment_map.h decides, once the image is read).
void PbrtBuilder::image_infinite_light(const PbrtParams& ps, const std::string& file, float scale,
                                       const Transform& light_to_world) {
  EnvLightDesc env;
  env.image_path = resolve_(file, ps);
  // Messages name the scene file first: an included file is named here.
  env.element = (ps.file() == scene_.source_path ? "" : ps.file() + ": ") + ps.location(ps.line());
  env.format = EnvMapFormat::EqualArea;
  env.lat_long_if_not_square = true;
  env.light_to_world = light_to_world;
  env.scale = scale;
  if (const float e = ps.get_float("illuminance", -1.0f); e > 0.0f) env.illuminance = e;
  scene_.external_files.push_back(env.image_path);
  scene_.env_lights.push_back(std::move(env));
}

std::optional<PbrtAreaLight> PbrtBuilder::make_area_light(const std::string& type, const PbrtParams& ps) {
  if (type != "diffuse") {
    diag_.warn(ps, "area light " + in_quotes(type) + " is not supported; the shapes that follow do not emit");
    diag_.unsupported("pbrt area light " + in_quotes(type), LoadOutcome::Ignored);
    for (const PbrtParam& p : ps.params()) p.used = true;
    return std::nullopt;
  }
  PbrtAreaLight a;
  const float scale = ps.get_float("scale", 1.0f);
  a.two_sided = ps.get_bool("twosided", false);
  if (const auto f = ps.find_string("filename")) {
    if (ps.has("L")) ps.fail(ps.line(), "cannot have both \"L\" and \"filename\" (pbrt-v4 refuses it too)");
    EmissionImageDesc image;
    image.path = resolve_(*f, ps);
    image.element = (ps.file() == scene_.source_path ? "" : ps.file() + ": ") + ps.location(ps.line());
    scene_.external_files.push_back(image.path);
    a.image = std::move(image);
    a.radiance = Rgb(scale);
  } else {
    a.radiance = light_spectrum(ps, "L") * scale;
  }
  if (ps.has("power")) {
    ps.get_float("power", -1.0f);
    diag_.warn(ps, "\"power\" is not supported for area lights; the radiance is \"L\" x \"scale\"");
    diag_.unsupported("area-light \"power\"");
  }
  diag_.report_unused(ps);
  return a;
}

}  // namespace kiln
