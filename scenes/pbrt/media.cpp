// pbrt-v4 MakeNamedMedium directives into SceneDesc::media (scenes/scene.h), with pbrt-v4's parameter names and
// defaults; renderer/world builds them (media/).
//   common        "string type" (required), "float g" (0; |g| <= 1, clamped to 0.99 as pbrt-v4 evaluates it),
//                 "spectrum sigma_a" / "sigma_s" (1; not negative), "float scale" (1)
//   homogeneous   "string preset" (a measured medium, below; unknown names are warned), "spectrum Le" (0),
//                 "float Lescale" (1)
//   uniformgrid   "float density" (nx ny nz values, not negative), "integer nx ny nz" (1), "point3 p0 p1" (0 0 0,
//                 1 1 1), "spectrum Le" with "float Lescale" (one value or nx ny nz), or "float temperature"
//                 (nx ny nz values) with "temperatureoffset" (alias "temperaturecutoff") and "temperaturescale"
//   rgbgrid       "rgb sigma_a" / "sigma_s" / "Le" (nx ny nz each; one of the first two required, Le needs
//                 sigma_a), "integer nx ny nz", "point3 p0 p1", "float Lescale"
//   nanovdb       "string filename" (required; resolved like Include, appended to SceneDesc::external_files),
//                 "string gridname" ("density"), "string temperaturename" ("temperature"), "float Lescale",
//                 "temperatureoffset" / "temperaturecutoff", "temperaturescale"
//   cloud         "float density" (1, not negative), "float wispiness" (1, not negative), "float frequency" (5,
//                 positive), "point3 p0 p1" (0 0 0, 1 1 1); "scale" multiplies sigma_a and sigma_s as for the other
//                 media (pbrt-v4's cloud does not read it and stops on it as an unused parameter)
// Every mistake (a lattice of the wrong length, a negative coefficient, an unknown type, a missing or non-NanoVDB
// file) is a kiln::Error naming file and line.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>

#include "core/error.h"
#include "media/emission_table.h"
#include "scenes/pbrt/builder.h"

namespace kiln {
namespace {

// pbrt-v4 evaluates Henyey-Greenstein with g clamped to this (the phase function is a spike beyond it).
constexpr float kMaxPhaseAsymmetry = 0.99f;
// NanoVDB files start with this 64-bit magic number ("NanoVDB0", little-endian).
constexpr uint64_t kNanoVdbMagic = 0x304244566f6e614eull;

// Measured scattering of real media (reduced scattering and absorption coefficients, per mm), as pbrt-v4's
// "preset" names them: Jensen, Marschner, Levoy and Hanrahan, "A Practical Model for Subsurface Light Transport"
// (SIGGRAPH 2001), and Narasimhan, Gupta, Donner, Ramamoorthi, Nayar and Jensen, "Acquiring Scattering Properties
// of Participating Media by Dilution" (SIGGRAPH 2006).
struct MeasuredMedium {
  const char* name;
  Rgb sigma_s, sigma_a;
};
constexpr MeasuredMedium kMeasuredMedia[] = {
    {"Apple", {2.29f, 2.39f, 1.97f}, {0.0030f, 0.0034f, 0.046f}},
    {"Chicken1", {0.15f, 0.21f, 0.38f}, {0.015f, 0.077f, 0.19f}},
    {"Chicken2", {0.19f, 0.25f, 0.32f}, {0.018f, 0.088f, 0.20f}},
    {"Cream", {7.38f, 5.47f, 3.15f}, {0.0002f, 0.0028f, 0.0163f}},
    {"Ketchup", {0.18f, 0.07f, 0.03f}, {0.061f, 0.97f, 1.45f}},
    {"Marble", {2.19f, 2.62f, 3.00f}, {0.0021f, 0.0041f, 0.0071f}},
    {"Potato", {0.68f, 0.70f, 0.55f}, {0.0024f, 0.0090f, 0.12f}},
    {"Skimmilk", {0.70f, 1.22f, 1.90f}, {0.0014f, 0.0025f, 0.0142f}},
    {"Skin1", {0.74f, 0.88f, 1.01f}, {0.032f, 0.17f, 0.48f}},
    {"Skin2", {1.09f, 1.59f, 1.79f}, {0.013f, 0.070f, 0.145f}},
    {"Spectralon", {11.6f, 20.4f, 14.9f}, {0.00f, 0.00f, 0.00f}},
    {"Wholemilk", {2.55f, 3.21f, 3.77f}, {0.0011f, 0.0024f, 0.014f}},
    {"Lowfat Milk", {0.89187f, 1.5136f, 2.532f}, {0.002875f, 0.00575f, 0.0115f}},
    {"Reduced Milk", {2.4858f, 3.1669f, 4.5214f}, {0.0025556f, 0.0051111f, 0.012778f}},
    {"Regular Milk", {4.5513f, 5.8294f, 7.136f}, {0.0015333f, 0.0046f, 0.019933f}},
    {"Espresso", {0.72378f, 0.84557f, 1.0247f}, {4.7984f, 6.5751f, 8.8493f}},
    {"Mint Mocha Coffee", {0.31602f, 0.38538f, 0.48131f}, {3.772f, 5.8228f, 7.82f}},
    {"Lowfat Soy Milk", {0.30576f, 0.34233f, 0.61664f}, {0.0014375f, 0.0071875f, 0.035937f}},
    {"Regular Soy Milk", {0.59223f, 0.73866f, 1.4693f}, {0.0019167f, 0.0095833f, 0.065167f}},
    {"Lowfat Chocolate Milk", {0.64925f, 0.83916f, 1.1057f}, {0.0115f, 0.0368f, 0.1564f}},
    {"Regular Chocolate Milk", {1.4585f, 2.1289f, 2.9527f}, {0.010063f, 0.043125f, 0.14375f}},
    {"Coke", {8.9053e-05f, 8.372e-05f, 0.0f}, {0.10014f, 0.16503f, 0.2468f}},
    {"Pepsi", {6.1697e-05f, 4.2564e-05f, 0.0f}, {0.091641f, 0.14158f, 0.20729f}},
    {"Sprite", {6.0306e-06f, 6.4139e-06f, 6.5504e-06f}, {0.001886f, 0.0018308f, 0.0020025f}},
    {"Gatorade", {0.0024574f, 0.003007f, 0.0037325f}, {0.024794f, 0.019289f, 0.008878f}},
    {"Chardonnay", {1.7982e-05f, 1.3758e-05f, 1.2023e-05f}, {0.010782f, 0.011855f, 0.023997f}},
    {"White Zinfandel", {1.7501e-05f, 1.9069e-05f, 1.288e-05f}, {0.012072f, 0.016184f, 0.019843f}},
    {"Merlot", {2.1129e-05f, 0.0f, 0.0f}, {0.11632f, 0.25191f, 0.29434f}},
    {"Budweiser Beer", {2.4356e-05f, 2.4079e-05f, 1.0564e-05f}, {0.011492f, 0.024911f, 0.057786f}},
    {"Coors Light Beer", {5.0922e-05f, 4.301e-05f, 0.0f}, {0.006164f, 0.013984f, 0.034983f}},
    {"Clorox", {0.0024035f, 0.0031373f, 0.003991f}, {0.0033542f, 0.014892f, 0.026297f}},
    {"Apple Juice", {0.00013612f, 0.00015836f, 0.000227f}, {0.012957f, 0.023741f, 0.052184f}},
    {"Cranberry Juice", {0.00010402f, 0.00011646f, 7.8139e-05f}, {0.039437f, 0.094223f, 0.12426f}},
    {"Grape Juice", {5.382e-05f, 0.0f, 0.0f}, {0.10404f, 0.23958f, 0.29325f}},
    {"Ruby Grapefruit Juice", {0.011002f, 0.010927f, 0.011036f}, {0.085867f, 0.18314f, 0.25262f}},
    {"White Grapefruit Juice", {0.22826f, 0.23998f, 0.32748f}, {0.0138f, 0.018831f, 0.056781f}},
    {"Shampoo", {0.0007176f, 0.0008303f, 0.0009016f}, {0.014107f, 0.045693f, 0.061717f}},
    {"Strawberry Shampoo", {0.00015671f, 0.00015947f, 1.518e-05f}, {0.01449f, 0.05796f, 0.075823f}},
    {"Head & Shoulders Shampoo", {0.023805f, 0.028804f, 0.034306f}, {0.084621f, 0.15688f, 0.20365f}},
    {"Lemon Tea Powder", {0.040224f, 0.045264f, 0.051081f}, {2.4288f, 4.5757f, 7.2127f}},
    {"Orange Powder", {0.00015617f, 0.00017482f, 0.0001762f}, {0.001449f, 0.003441f, 0.007863f}},
    {"Pink Lemonade Powder", {0.00012103f, 0.00013073f, 0.00012528f}, {0.001165f, 0.002366f, 0.003195f}},
    {"Cappuccino Powder", {1.8436f, 2.5851f, 2.1662f}, {35.844f, 49.547f, 61.084f}},
    {"Salt Powder", {0.027333f, 0.032451f, 0.031979f}, {0.28415f, 0.3257f, 0.34148f}},
    {"Sugar Powder", {0.00022272f, 0.00025513f, 0.000271f}, {0.012638f, 0.031051f, 0.050124f}},
    {"Suisse Mocha Powder", {2.7979f, 3.5452f, 4.3365f}, {17.502f, 27.004f, 35.433f}},
    {"Pacific Ocean Surface Water", {0.0001764f, 0.00032095f, 0.00019617f}, {0.031845f, 0.031324f, 0.030147f}},
};

const MeasuredMedium* measured_medium(const std::string& name) {
  for (const MeasuredMedium& m : kMeasuredMedia)
    if (name == m.name) return &m;
  return nullptr;
}

Rgb clamp_zero(Rgb c) { return {std::max(0.0f, c.r), std::max(0.0f, c.g), std::max(0.0f, c.b)}; }

// Planck's law, up to a constant factor, at a wavelength in nanometres.
double planck(double lambda_nm, double kelvin) {
  constexpr double kC2 = 1.4387768775e7;  // h c / k in nm K
  const double l = lambda_nm;
  return 1.0 / (l * l * l * l * l * (std::exp(kC2 / (l * kelvin)) - 1.0));
}

// pbrt-v4's temperature emission: a blackbody spectrum normalised to 1 at its peak (not to unit luminance), as the
// RGB film records it: XYZ against the colour-matching functions over the integral of y-bar (a flat spectrum of 1
// has luminance 1), then linear sRGB. Tabulated at the temperatures of media/emission_table.h.
std::vector<Rgb> blackbody_table() {
  constexpr int kFirstNm = 360, kLastNm = 830;
  constexpr double kWienNmK = 2.897771955e6;  // Wien's displacement constant in nm K
  std::vector<Vec3f> cmf;
  double y_integral = 0.0;
  for (int l = kFirstNm; l <= kLastNm; ++l) {
    cmf.push_back(cie_xyz_matching(float(l)));
    y_integral += cmf.back().y;
  }
  std::vector<Rgb> t(kEmissionTableSize);
  for (int i = 0; i < kEmissionTableSize; ++i) {
    const double kelvin = emission_table_kelvin(i), peak = planck(kWienNmK / kelvin, kelvin);
    double xyz[3] = {0.0, 0.0, 0.0};
    for (int l = kFirstNm; l <= kLastNm; ++l) {
      const double b = planck(l, kelvin) / peak;
      const Vec3f& m = cmf[size_t(l - kFirstNm)];
      xyz[0] += b * m.x;
      xyz[1] += b * m.y;
      xyz[2] += b * m.z;
    }
    t[size_t(i)] = clamp_zero(xyz_to_linear_srgb(
        Vec3f(float(xyz[0] / y_integral), float(xyz[1] / y_integral), float(xyz[2] / y_integral))));
  }
  return t;
}

Rgb coefficient(const PbrtParams& ps, const std::string& name) {
  const Rgb c = ps.find_spectrum(name, SpectrumUse::Unbounded).value_or(Rgb(1.0f));
  if (c.has_negative() || !c.is_finite()) ps.fail(ps.line(), in_quotes(name) + " must not be negative");
  return c;
}

float non_negative(const PbrtParams& ps, const std::string& name, float def) {
  const float v = ps.get_float(name, def);
  if (v < 0.0f) ps.fail(ps.line(), in_quotes(name) + " must not be negative");
  return v;
}

// "p0" and "p1": a medium's box in its own space.
void medium_box(const PbrtParams& ps, Vec3f& p0, Vec3f& p1) {
  p0 = ps.find_point3("p0").value_or(Vec3f(0.0f));
  p1 = ps.find_point3("p1").value_or(Vec3f(1.0f));
  if (!(p0.x < p1.x && p0.y < p1.y && p0.z < p1.z))
    ps.fail(ps.line(), "\"p0\" must lie below \"p1\" on every axis (the medium's box is empty)");
}

MediumLattice lattice(const PbrtParams& ps) {
  MediumLattice l;
  l.nx = ps.get_int("nx", 1);
  l.ny = ps.get_int("ny", 1);
  l.nz = ps.get_int("nz", 1);
  if (l.nx < 1 || l.ny < 1 || l.nz < 1) ps.fail(ps.line(), "\"nx\", \"ny\" and \"nz\" must be at least 1");
  medium_box(ps, l.p0, l.p1);
  return l;
}

template <typename T>
void check_count(const PbrtParams& ps, const std::string& name, const std::vector<T>& v, const MediumLattice& l) {
  if (v.size() != l.count())
    ps.fail(ps.line(), in_quotes(name) + " has " + std::to_string(v.size()) + " values; nx * ny * nz = " +
                           std::to_string(l.nx) + " * " + std::to_string(l.ny) + " * " + std::to_string(l.nz) +
                           " = " + std::to_string(l.count()));
}

void check_non_negative(const PbrtParams& ps, const std::string& name, const std::vector<float>& v) {
  for (size_t i = 0; i < v.size(); ++i)
    if (v[i] < 0.0f) ps.fail(ps.line(), in_quotes(name) + " value " + std::to_string(i) + " is negative");
}

void temperature_params(const PbrtParams& ps, float& offset, float& scale) {
  offset = ps.get_float("temperatureoffset", ps.get_float("temperaturecutoff", 0.0f));
  scale = ps.get_float("temperaturescale", 1.0f);
}

HomogeneousMediumDesc homogeneous(const PbrtParams& ps, float scale, PbrtDiagnostics& diag) {
  HomogeneousMediumDesc h;
  const std::string preset = ps.get_string("preset", "");
  const MeasuredMedium* measured = preset.empty() ? nullptr : measured_medium(preset);
  if (!preset.empty() && !measured) diag.warn(ps, "no measured medium named " + in_quotes(preset) + "; ignored");
  h.sigma_a = measured ? measured->sigma_a : coefficient(ps, "sigma_a");
  h.sigma_s = measured ? measured->sigma_s : coefficient(ps, "sigma_s");
  if (measured)  // pbrt-v4 reads neither when the preset is found
    for (const PbrtParam& p : ps.params())
      if (p.name == "sigma_a" || p.name == "sigma_s") {
        diag.warn(ps, in_quotes(p.name) + " is ignored: preset " + in_quotes(preset) + " gives it");
        p.used = true;
      }
  h.sigma_a = h.sigma_a * scale;
  h.sigma_s = h.sigma_s * scale;
  h.le = ps.find_spectrum("Le", SpectrumUse::Illuminant).value_or(Rgb(0.0f)) * non_negative(ps, "Lescale", 1.0f);
  return h;
}

GridMediumDesc uniform_grid(const PbrtParams& ps, float scale) {
  GridMediumDesc g;
  g.lattice = lattice(ps);
  g.density = ps.get_floats("density");
  if (g.density.empty()) ps.fail(ps.line(), "a \"uniformgrid\" medium needs a \"density\" array");
  check_count(ps, "density", g.density, g.lattice);
  check_non_negative(ps, "density", g.density);
  g.sigma_a = coefficient(ps, "sigma_a") * scale;
  g.sigma_s = coefficient(ps, "sigma_s") * scale;
  g.temperature = ps.get_floats("temperature");
  const auto le = ps.find_spectrum("Le", SpectrumUse::Illuminant);
  if (!g.temperature.empty()) {
    if (le) ps.fail(ps.line(), "give either \"Le\" or \"temperature\", not both");
    check_count(ps, "temperature", g.temperature, g.lattice);
    temperature_params(ps, g.temperature_offset, g.temperature_scale);
  }
  g.le = le.value_or(Rgb(0.0f));
  g.le_scale = ps.get_floats("Lescale");
  if (g.le_scale.empty()) g.le_scale = {1.0f};
  else if (g.le_scale.size() != 1) check_count(ps, "Lescale", g.le_scale, g.lattice);
  check_non_negative(ps, "Lescale", g.le_scale);
  return g;
}

RgbGridMediumDesc rgb_grid(const PbrtParams& ps, float scale) {
  RgbGridMediumDesc g;
  g.lattice = lattice(ps);
  g.sigma_a = ps.get_rgbs("sigma_a");
  g.sigma_s = ps.get_rgbs("sigma_s");
  g.le = ps.get_rgbs("Le");
  if (g.sigma_a.empty() && g.sigma_s.empty())
    ps.fail(ps.line(), "an \"rgbgrid\" medium needs \"sigma_a\" or \"sigma_s\" (or both)");
  if (!g.le.empty() && g.sigma_a.empty()) ps.fail(ps.line(), "\"Le\" of an \"rgbgrid\" medium needs \"sigma_a\"");
  const std::pair<const char*, const std::vector<Rgb>*> lattices[] = {
      {"sigma_a", &g.sigma_a}, {"sigma_s", &g.sigma_s}, {"Le", &g.le}};
  for (const auto& [name, values] : lattices) {
    if (values->empty()) continue;
    check_count(ps, name, *values, g.lattice);
    for (const Rgb& c : *values)
      if (c.has_negative()) ps.fail(ps.line(), in_quotes(name) + " has a negative component");
  }
  g.scale = scale;
  g.le_scale = non_negative(ps, "Lescale", 1.0f);
  return g;
}

// A NanoVDB file is opened when the world is built; its first bytes are checked here so that a wrong file is
// reported at the directive's line.
void check_nanovdb_file(const PbrtParams& ps, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint64_t magic = 0;
  if (!in) ps.fail(ps.line(), "cannot open " + in_quotes(path));
  in.read(reinterpret_cast<char*>(&magic), sizeof magic);
  if (!in || magic != kNanoVdbMagic) ps.fail(ps.line(), in_quotes(path) + " is not a NanoVDB file (.nvdb)");
}

NanoVdbMediumDesc nanovdb(const PbrtParams& ps, float scale, const PbrtResolve& resolve) {
  NanoVdbMediumDesc v;
  const auto file = ps.find_string("filename");
  if (!file) ps.fail(ps.line(), "a \"nanovdb\" medium needs a \"filename\"");
  v.path = resolve(*file, ps.line());
  check_nanovdb_file(ps, v.path);
  v.density_grid = ps.get_string("gridname", "density");
  v.temperature_grid = ps.get_string("temperaturename", "temperature");
  v.sigma_a = coefficient(ps, "sigma_a") * scale;
  v.sigma_s = coefficient(ps, "sigma_s") * scale;
  v.le_scale = non_negative(ps, "Lescale", 1.0f);
  temperature_params(ps, v.temperature_offset, v.temperature_scale);
  return v;
}

CloudMediumDesc cloud(const PbrtParams& ps, float scale) {
  CloudMediumDesc c;
  medium_box(ps, c.p0, c.p1);
  c.sigma_a = coefficient(ps, "sigma_a") * scale;
  c.sigma_s = coefficient(ps, "sigma_s") * scale;
  c.density = non_negative(ps, "density", c.density);
  c.wispiness = non_negative(ps, "wispiness", c.wispiness);
  c.frequency = ps.get_float("frequency", c.frequency);
  if (!(c.frequency > 0.0f)) ps.fail(ps.line(), "\"frequency\" must be positive");
  return c;
}

bool has_temperature(const MediumDesc& m) {
  if (const auto* g = std::get_if<GridMediumDesc>(&m.params)) return !g->temperature.empty();
  return std::holds_alternative<NanoVdbMediumDesc>(m.params);
}

}  // namespace

void PbrtBuilder::make_medium(const std::string& name, const PbrtParams& ps, const Transform& medium_to_world,
                              const PbrtResolve& resolve) {
  if (named_media_.count(name)) ps.fail(ps.line(), "a medium named " + in_quotes(name) + " is already defined");
  const auto type = ps.find_string("type");
  if (!type) ps.fail(ps.line(), "a medium needs a \"string type\"");
  MediumDesc m;
  m.name = name;
  m.element = ps.file() + ": " + ps.location(ps.line());
  m.to_world = medium_to_world;
  const float g = ps.get_float("g", 0.0f);
  if (!(std::abs(g) <= 1.0f)) ps.fail(ps.line(), "\"g\" must lie in [-1, 1]");
  m.g = std::clamp(g, -kMaxPhaseAsymmetry, kMaxPhaseAsymmetry);
  const float scale = non_negative(ps, "scale", 1.0f);
  if (*type == "homogeneous") {
    m.params = homogeneous(ps, scale, diag_);
  } else if (*type == "uniformgrid") {
    m.params = uniform_grid(ps, scale);
  } else if (*type == "rgbgrid") {
    m.params = rgb_grid(ps, scale);
  } else if (*type == "nanovdb") {
    NanoVdbMediumDesc v = nanovdb(ps, scale, resolve);
    scene_.external_files.push_back(v.path);
    m.params = std::move(v);
  } else if (*type == "cloud") {
    m.params = cloud(ps, scale);
  } else {
    ps.fail(ps.line(), "unknown medium type " + in_quotes(*type) +
                           " (homogeneous, uniformgrid, rgbgrid, nanovdb, cloud)");
  }
  if (has_temperature(m)) m.blackbody = blackbody_table();
  diag_.report_unused(ps);
  named_media_[name] = int(scene_.media.size());
  scene_.media.push_back(std::move(m));
}

std::optional<int> PbrtBuilder::named_medium(const std::string& name) const {
  const auto it = named_media_.find(name);
  if (it == named_media_.end()) return std::nullopt;
  return it->second;
}

}  // namespace kiln
