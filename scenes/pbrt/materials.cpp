// pbrt-v4 materials into MaterialDesc::pbrt (scenes/scene.h); scenes/material_mapping.h builds them.
#include "scenes/pbrt/builder.h"

#include <algorithm>

#include "core/error.h"

namespace kiln {

void PbrtBuilder::read_roughness(const PbrtParams& ps, PbrtMaterialDesc& pm) {
  const TexturedFloat r = float_param(ps, "roughness", 0.0f);
  pm.uroughness = ps.has("uroughness") ? float_param(ps, "uroughness", r.value) : r;
  pm.vroughness = ps.has("vroughness") ? float_param(ps, "vroughness", r.value) : r;
  if (pm.uroughness.value < 0.0f || pm.vroughness.value < 0.0f) ps.fail(ps.line(), "roughness must not be negative");
  pm.remap_roughness = ps.get_bool("remaproughness", true);
}

// pbrt-v4's eta is a float or a spectrum; Kiln also takes a float texture.
TexturedFloat PbrtBuilder::interface_eta(const PbrtParams& ps) {
  if (ps.find_texture("eta")) return float_param(ps, "eta", kPbrtDefaultDielectricEta);
  bool spectral = false;
  const float eta = ps.find_float_or_spectrum("eta", &spectral).value_or(kPbrtDefaultDielectricEta);
  if (!(eta > 0.0f)) ps.fail(ps.line(), "\"eta\" must be positive");
  if (spectral) {
    diag_.warn(ps, "a spectral \"eta\" is rendered without dispersion (eta = " + std::to_string(eta) + ")");
    diag_.unsupported("dispersion (spectral eta)");
  }
  return {eta, -1};
}

// Bump mapping by a float texture ("displacement") or a tangent-space normal map image ("normalmap"); pbrt-v4 uses
// the normal map when both are given.
void PbrtBuilder::read_bump(const PbrtParams& ps, PbrtMaterialDesc& pm) {
  if (ps.has("displacement")) {
    const TexturedFloat d = float_param(ps, "displacement", 0.0f);
    pm.displacement = d.texture;  // a constant displacement moves the surface without bending its normal
  }
  if (const auto file = ps.find_string("normalmap")) {
    ImageTextureDesc image;
    image.path = resolve_(*file, ps);
    image.encoding = ImageEncoding::Linear;  // pbrt-v4 reads normal maps without decoding
    std::string name = Error::format(ps.file(), ps.location(ps.line()), "normal map " + in_quotes(*file));
    pm.normal_map = add_image_texture(name, image, false);
  }
}

int PbrtBuilder::make_material(const std::string& type, const PbrtParams& ps) {
  MaterialDesc d;
  d.id = int(scene_.materials.size()) + 1;
  PbrtMaterialDesc pm;
  read_bump(ps, pm);
  if (type == "diffuse") {
    pm.kind = PbrtMaterialKind::Diffuse;
    pm.reflectance = spectrum_param(ps, "reflectance", SpectrumUse::Albedo, Rgb(kPbrtDefaultReflectance));
  } else if (type == "coateddiffuse") {
    pm.kind = PbrtMaterialKind::CoatedDiffuse;
    pm.reflectance = spectrum_param(ps, "reflectance", SpectrumUse::Albedo, Rgb(kPbrtDefaultReflectance));
    read_roughness(ps, pm);
    pm.thickness = float_param(ps, "thickness", kPbrtDefaultCoatThickness);
    pm.eta = interface_eta(ps);
    pm.albedo = spectrum_param(ps, "albedo", SpectrumUse::Albedo, Rgb(0.0f));
    pm.g = float_param(ps, "g", 0.0f);
    pm.max_depth = ps.get_int("maxdepth", kPbrtDefaultCoatMaxDepth);
    pm.n_samples = ps.get_int("nsamples", 1);
    if (pm.thickness.value < 0.0f) ps.fail(ps.line(), "\"thickness\" must not be negative");
    if (pm.g.value <= -1.0f || pm.g.value >= 1.0f) ps.fail(ps.line(), "\"g\" must lie in (-1, 1)");
    if (pm.max_depth < 1 || pm.n_samples < 1) ps.fail(ps.line(), "\"maxdepth\" and \"nsamples\" must be at least 1");
  } else if (type == "conductor") {
    pm.kind = PbrtMaterialKind::Conductor;
    if (ps.has("reflectance")) {
      pm.conductor_by_reflectance = true;
      pm.conductor_reflectance = spectrum_param(ps, "reflectance", SpectrumUse::Albedo, Rgb(1.0f));
    } else {
      pm.conductor_eta = spectrum_param(ps, "eta", SpectrumUse::Unbounded, pm.conductor_eta.value);
      pm.conductor_k = spectrum_param(ps, "k", SpectrumUse::Unbounded, pm.conductor_k.value);
    }
    read_roughness(ps, pm);
  } else if (type == "dielectric") {
    pm.kind = PbrtMaterialKind::Dielectric;
    pm.eta = interface_eta(ps);
    read_roughness(ps, pm);
  } else if (type == "interface" || type.empty() || type == "none") {
    pm.kind = PbrtMaterialKind::Interface;
  } else {
    diag_.warn(ps, "material " + in_quotes(type) + " is not supported; rendered as pbrt's default (diffuse, 0.5)");
    diag_.unsupported("pbrt material " + in_quotes(type));
    for (const PbrtParam& p : ps.params()) p.used = true;
    pm.kind = PbrtMaterialKind::Diffuse;
    pm = PbrtMaterialDesc{};
    pm.reflectance = {Rgb(kPbrtDefaultReflectance), -1};
  }
  d.pbrt = pm;
  diag_.report_unused(ps);
  scene_.materials.push_back(d);
  return int(scene_.materials.size()) - 1;
}


void PbrtBuilder::make_named_material(const std::string& name, const PbrtParams& ps) {
  if (named_materials_.count(name)) ps.fail(ps.line(), "material " + in_quotes(name) + " is defined twice");
  const auto type = ps.find_string("type");
  if (!type) ps.fail(ps.line(), "needs \"string type\" (diffuse, conductor, dielectric, coateddiffuse, ...)");
  named_materials_[name] = make_material(*type, ps);
}

std::optional<int> PbrtBuilder::named_material(const std::string& name) const {
  const auto it = named_materials_.find(name);
  if (it == named_materials_.end()) return std::nullopt;
  return it->second;
}

int PbrtBuilder::default_material(const std::string& file) {
  if (default_material_ < 0) {
    PbrtParams none(file, "default material", 0);
    default_material_ = make_material("diffuse", none);
  }
  return default_material_;
}

}  // namespace kiln
