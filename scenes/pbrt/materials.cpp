// pbrt-v4 materials into MaterialDesc::pbrt (scenes/scene.h); scenes/material_mapping.h builds them.
#include "scenes/pbrt/builder.h"

#include <algorithm>

#include "core/error.h"

namespace kiln {

void PbrtBuilder::read_roughness(const PbrtParams& ps, const std::string& prefix, TexturedFloat& u, TexturedFloat& v) {
  const TexturedFloat r = float_param(ps, prefix + "roughness", 0.0f);
  u = ps.has(prefix + "uroughness") ? float_param(ps, prefix + "uroughness", r.value) : r;
  v = ps.has(prefix + "vroughness") ? float_param(ps, prefix + "vroughness", r.value) : r;
  if (u.value < 0.0f || v.value < 0.0f) ps.fail(ps.line(), in_quotes(prefix + "roughness") + " must not be negative");
}

// pbrt-v4's eta is a float or a spectrum; Kiln also takes a float texture.
TexturedFloat PbrtBuilder::interface_eta(const PbrtParams& ps, const std::string& name) {
  if (ps.find_texture(name)) return float_param(ps, name, kPbrtDefaultDielectricEta);
  bool spectral = false;
  const float eta = ps.find_float_or_spectrum(name, &spectral).value_or(kPbrtDefaultDielectricEta);
  if (!(eta > 0.0f)) ps.fail(ps.line(), in_quotes(name) + " must be positive");
  if (spectral) {
    diag_.warn(ps, "a spectral " + in_quotes(name) + " is rendered without dispersion (eta = " + std::to_string(eta) + ")");
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

// A conductor's "eta" and "k" (pbrt's default: copper), or its "reflectance"; prefix "conductor." for the base of a
// coatedconductor. pbrt-v4 rejects "reflectance" together with "eta" or "k". eta and k given as spectra (or left at
// pbrt's default, copper's spectra) are reduced together (scenes/pbrt/spectrum.h); an RGB or textured one makes each
// reduced on its own.
void PbrtBuilder::read_conductor(const PbrtParams& ps, const std::string& prefix, PbrtMaterialDesc& pm) {
  const std::string eta_name = prefix + "eta", k_name = prefix + "k";
  if (ps.has("reflectance")) {
    if (ps.has(eta_name) || ps.has(k_name))
      ps.fail(ps.line(), "gives both \"reflectance\" and " + in_quotes(eta_name) + " / " + in_quotes(k_name) +
                             " (pbrt-v4 takes one or the other)");
    pm.conductor_by_reflectance = true;
    pm.conductor_reflectance = spectrum_param(ps, "reflectance", SpectrumUse::Albedo, Rgb(1.0f));
    return;
  }
  const auto spectral = [&](const std::string& name, std::string_view copper) {
    return ps.has(name) ? ps.find_piecewise_spectrum(name) : named_spectrum(copper);
  };
  const std::optional<PiecewiseSpectrum> eta = spectral(eta_name, "metal-Cu-eta"), k = spectral(k_name, "metal-Cu-k");
  if (eta && k) {
    const RgbComplexIor ior = conductor_rgb_ior(*eta, *k);
    pm.conductor_eta = ior.eta;
    pm.conductor_k = ior.k;
    return;
  }
  const auto reduced = [&](const std::optional<PiecewiseSpectrum>& s, const std::string& name) {
    return s ? TexturedRgb(spectrum_rgb(*s, SpectrumUse::Unbounded))
             : spectrum_param(ps, name, SpectrumUse::Unbounded, Rgb(1.0f));
  };
  pm.conductor_eta = reduced(eta, eta_name);
  pm.conductor_k = reduced(k, k_name);
}

// The random walk's parameters of coateddiffuse and coatedconductor.
void PbrtBuilder::read_layers(const PbrtParams& ps, PbrtMaterialDesc& pm) {
  pm.thickness = float_param(ps, "thickness", kPbrtDefaultCoatThickness);
  pm.albedo = spectrum_param(ps, "albedo", SpectrumUse::Albedo, Rgb(0.0f));
  pm.g = float_param(ps, "g", 0.0f);
  pm.max_depth = ps.get_int("maxdepth", kPbrtDefaultCoatMaxDepth);
  pm.n_samples = ps.get_int("nsamples", 1);
  pm.remap_roughness = ps.get_bool("remaproughness", true);
  if (pm.thickness.value < 0.0f) ps.fail(ps.line(), "\"thickness\" must not be negative");
  if (pm.g.value <= -1.0f || pm.g.value >= 1.0f) ps.fail(ps.line(), "\"g\" must lie in (-1, 1)");
  if (pm.max_depth < 1 || pm.n_samples < 1) ps.fail(ps.line(), "\"maxdepth\" and \"nsamples\" must be at least 1");
}

void PbrtBuilder::read_mix(const PbrtParams& ps, MaterialDesc& d) {
  const std::vector<std::string> names = ps.get_strings("materials");
  if (names.size() != 2)
    ps.fail(ps.line(), "\"materials\" must name two materials, got " + std::to_string(names.size()));
  MaterialMixDesc mix;
  mix.amount = float_param(ps, "amount", kPbrtDefaultMixAmount);
  d.mix = mix;
  pending_mixes_.push_back({int(scene_.materials.size()), {names[0], names[1]}, ps.file(), ps.context(), ps.line()});
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
    read_roughness(ps, "", pm.uroughness, pm.vroughness);
    pm.eta = interface_eta(ps, "eta");
    read_layers(ps, pm);
  } else if (type == "coatedconductor") {
    pm.kind = PbrtMaterialKind::CoatedConductor;
    read_roughness(ps, "interface.", pm.uroughness, pm.vroughness);
    pm.eta = interface_eta(ps, "interface.eta");
    read_roughness(ps, "conductor.", pm.conductor_uroughness, pm.conductor_vroughness);
    read_conductor(ps, "conductor.", pm);
    read_layers(ps, pm);
  } else if (type == "conductor") {
    pm.kind = PbrtMaterialKind::Conductor;
    read_conductor(ps, "", pm);
    read_roughness(ps, "", pm.uroughness, pm.vroughness);
    pm.remap_roughness = ps.get_bool("remaproughness", true);
  } else if (type == "dielectric") {
    pm.kind = PbrtMaterialKind::Dielectric;
    pm.eta = interface_eta(ps, "eta");
    read_roughness(ps, "", pm.uroughness, pm.vroughness);
    pm.remap_roughness = ps.get_bool("remaproughness", true);
  } else if (type == "thindielectric") {
    pm.kind = PbrtMaterialKind::ThinDielectric;
    pm.eta = interface_eta(ps, "eta");
  } else if (type == "diffusetransmission") {
    pm.kind = PbrtMaterialKind::DiffuseTransmission;
    pm.reflectance = spectrum_param(ps, "reflectance", SpectrumUse::Albedo, Rgb(kPbrtDefaultDiffuseTransmission));
    pm.transmittance = spectrum_param(ps, "transmittance", SpectrumUse::Albedo, Rgb(kPbrtDefaultDiffuseTransmission));
    pm.scale = ps.get_float("scale", 1.0f);
    if (!(pm.scale >= 0.0f)) ps.fail(ps.line(), "\"scale\" must not be negative");
  } else if (type == "mix") {
    read_mix(ps, d);
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
  if (!d.mix) d.pbrt = pm;
  diag_.report_unused(ps);
  scene_.materials.push_back(d);
  return int(scene_.materials.size()) - 1;
}

// Mixes name their components by MakeNamedMaterial names, which may be defined after the mix (pbrt-v4 creates
// anonymous materials after all named ones): they are resolved once the whole file is read. A missing name, or mixes
// that contain each other, are errors at the mix's line.
void PbrtBuilder::resolve_mixes() {
  for (const PendingMix& pm : pending_mixes_) {
    MaterialMixDesc& mix = *scene_.materials[size_t(pm.material)].mix;
    for (size_t i = 0; i < 2; ++i) {
      const auto it = named_materials_.find(pm.names[i]);
      if (it == named_materials_.end())
        throw Error(pm.file, pm.where(), "\"materials\" names " + in_quotes(pm.names[i]) +
                                             ", which no MakeNamedMaterial defines");
      mix.materials[i] = it->second;
    }
  }
  for (const PendingMix& pm : pending_mixes_) {
    const std::vector<int> cycle = mix_cycle_from(pm.material);
    if (cycle.empty()) continue;
    std::string path;
    for (int m : cycle) path += (path.empty() ? "" : " -> ") + in_quotes(material_name(m));
    throw Error(pm.file, pm.where(), "mix materials contain each other: " + path);
  }
}

// The chain of mixes from `start` back to itself, empty when `start` is not on a cycle. Depth-first over the mix
// graph, whose out-degree is 2.
std::vector<int> PbrtBuilder::mix_cycle_from(int start) const {
  std::vector<int> path{start};
  std::vector<size_t> next_child{0};
  std::vector<bool> visited(scene_.materials.size(), false);
  visited[size_t(start)] = true;
  while (!path.empty()) {
    const auto& mix = scene_.materials[size_t(path.back())].mix;
    if (!mix || next_child.back() == 2) {
      path.pop_back();
      next_child.pop_back();
      continue;
    }
    const int child = mix->materials[next_child.back()++];
    if (child == start) {
      path.push_back(start);
      return path;
    }
    if (child < 0 || visited[size_t(child)]) continue;
    visited[size_t(child)] = true;
    path.push_back(child);
    next_child.push_back(0);
  }
  return {};
}

std::string PbrtBuilder::material_name(int index) const {
  for (const auto& [name, i] : named_materials_)
    if (i == index) return name;
  return "material #" + std::to_string(index + 1);
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
