// pbrt-v4 materials into MaterialDesc::pbrt (scenes/scene.h); scenes/material_mapping.h builds them.
#include "scenes/pbrt/builder.h"

#include <algorithm>

#include "core/error.h"

namespace kiln {

// A float parameter that may name a texture: constant textures are read, others warned (the default is used).
float PbrtBuilder::float_param(const PbrtParams& ps, const std::string& name, float def) {
  if (const auto tex = ps.find_texture(name)) {
    const PbrtTextureDef& t = texture_def(ps, *tex);
    if (t.is_float && t.value) return *t.value;
    texture_not_rendered(ps, name, *tex, t);
    return def;
  }
  return ps.get_float(name, def);
}

Rgb PbrtBuilder::spectrum_param(const PbrtParams& ps, const std::string& name, SpectrumUse use, Rgb def) {
  if (const auto tex = ps.find_texture(name)) {
    const PbrtTextureDef& t = texture_def(ps, *tex);
    if (!t.is_float && t.rgb) {
      if (use == SpectrumUse::Albedo && t.rgb->max_component() > 1.0f) {
        diag_.warn(ps, "texture " + in_quotes(*tex) + " used as " + in_quotes(name) + " exceeds 1; clamped");
        return Rgb(std::min(t.rgb->r, 1.0f), std::min(t.rgb->g, 1.0f), std::min(t.rgb->b, 1.0f));
      }
      return *t.rgb;
    }
    texture_not_rendered(ps, name, *tex, t);
    return def;
  }
  return ps.find_spectrum(name, use).value_or(def);
}


void PbrtBuilder::read_roughness(const PbrtParams& ps, PbrtMaterialDesc& pm) {
  const float r = float_param(ps, "roughness", 0.0f);
  pm.uroughness = ps.has("uroughness") ? float_param(ps, "uroughness", r) : r;
  pm.vroughness = ps.has("vroughness") ? float_param(ps, "vroughness", r) : r;
  if (pm.uroughness < 0.0f || pm.vroughness < 0.0f) ps.fail(ps.line(), "roughness must not be negative");
  pm.remap_roughness = ps.get_bool("remaproughness", true);
}

float PbrtBuilder::interface_eta(const PbrtParams& ps) {
  bool spectral = false;
  const float eta = ps.find_float_or_spectrum("eta", &spectral).value_or(kPbrtDefaultDielectricEta);
  if (!(eta > 0.0f)) ps.fail(ps.line(), "\"eta\" must be positive");
  if (spectral) {
    diag_.warn(ps, "a spectral \"eta\" is rendered without dispersion (eta = " + std::to_string(eta) + ")");
    diag_.unsupported("dispersion (spectral eta)");
  }
  return eta;
}

int PbrtBuilder::make_material(const std::string& type, const PbrtParams& ps) {
  MaterialDesc d;
  d.id = int(scene_.materials.size()) + 1;
  PbrtMaterialDesc pm;
  if (ps.has("displacement")) {
    ps.find_texture("displacement");
    diag_.warn(ps, "displacement is not rendered");
    diag_.unsupported("displacement (pbrt material \"displacement\")");
  }
  if (ps.has("normalmap")) {
    ps.find_string("normalmap");
    diag_.warn(ps, "normal maps are not rendered");
    diag_.unsupported("normal maps");
  }
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
    if (pm.thickness < 0.0f) ps.fail(ps.line(), "\"thickness\" must not be negative");
    if (pm.g <= -1.0f || pm.g >= 1.0f) ps.fail(ps.line(), "\"g\" must lie in (-1, 1)");
    if (pm.max_depth < 1 || pm.n_samples < 1) ps.fail(ps.line(), "\"maxdepth\" and \"nsamples\" must be at least 1");
  } else if (type == "conductor") {
    pm.kind = PbrtMaterialKind::Conductor;
    if (ps.has("reflectance")) {
      pm.conductor_reflectance = spectrum_param(ps, "reflectance", SpectrumUse::Albedo, Rgb(1.0f));
    } else {
      pm.conductor_eta = spectrum_param(ps, "eta", SpectrumUse::Unbounded, pm.conductor_eta);
      pm.conductor_k = spectrum_param(ps, "k", SpectrumUse::Unbounded, pm.conductor_k);
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
    pm.reflectance = Rgb(kPbrtDefaultReflectance);
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
  const int made = make_material(*type, ps);
  const auto forward = forward_materials_.find(name);
  if (forward == forward_materials_.end()) {
    named_materials_[name] = made;
    return;
  }
  fill_material_slot(forward->second.slot, made);
  named_materials_[name] = forward->second.slot;
  forward_materials_.erase(forward);
}

// Moves the material just made (the last one) into a slot reserved by a use before the definition.
void PbrtBuilder::fill_material_slot(int slot, int made) {
  MaterialDesc& d = scene_.materials[size_t(slot)];
  d = std::move(scene_.materials[size_t(made)]);
  d.id = slot + 1;
  if (made + 1 == int(scene_.materials.size())) scene_.materials.pop_back();
}

int PbrtBuilder::use_named_material(const std::string& name, const std::string& file, int line) {
  if (const auto it = named_materials_.find(name); it != named_materials_.end()) return it->second;
  if (const auto it = forward_materials_.find(name); it != forward_materials_.end()) return it->second.slot;
  MaterialDesc slot;
  slot.id = int(scene_.materials.size()) + 1;
  scene_.materials.push_back(slot);
  forward_materials_[name] = {int(scene_.materials.size()) - 1, file, line};
  return int(scene_.materials.size()) - 1;
}

void PbrtBuilder::finish_named_materials() {
  for (const auto& [name, f] : forward_materials_) {
    const std::string where = "line " + std::to_string(f.line) + " (NamedMaterial)";
    if (!diag_.allow_missing_files)
      throw Error(f.file, where, "no material named " + in_quotes(name) + " (MakeNamedMaterial defines them)");
    diag_.warn(f.file, f.line, "NamedMaterial",
               "no material named " + in_quotes(name) + " is defined (in a missing file?); pbrt's default is used");
    diag_.unsupported("named materials defined nowhere (left out: --allow-missing)");
    PbrtParams none(f.file, "default material", f.line);
    fill_material_slot(f.slot, make_material("diffuse", none));
  }
  forward_materials_.clear();
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
