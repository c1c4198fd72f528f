// pbrt-v4 materials coatedconductor, diffusetransmission, thindielectric and mix as the loader reads them (every
// parameter, mixes resolved by name once the file is read), and pbrt-v4's spectra: every named spectrum, blackbody
// parameters by use, .spd files by path, the conductor fit. Bad input names the file and the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scenes/pbrt/loader.h"
#include "scenes/pbrt/named_spectra.h"
#include "scenes/pbrt/spectrum.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

const std::string kHead =
    "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
    "\"integer yresolution\" 8\nWorldBegin\n";  // the world starts on line 5

std::string error_of(const std::string& text, const std::string& path = "inline.pbrt") {
  try {
    parse_pbrt(text, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string tmp(const std::string& sub) {
  const fs::path d = fs::path(KILN_TEST_TMP) / "pbrt_materials" / sub;
  fs::create_directories(d);
  return d.string();
}

const PbrtMaterialDesc& only_pbrt(const SceneDesc& s) { return *s.materials.back().pbrt; }

// ---- materials ----

TEST(PbrtMaterials, CoatedConductorReadsEveryParameter) {
  const SceneDesc s = parse_pbrt(kHead +
                                     "Material \"coatedconductor\" \"float interface.uroughness\" 0.1 "
                                     "\"float interface.vroughness\" 0.2 \"float interface.eta\" 1.4 "
                                     "\"float conductor.roughness\" 0.3 \"spectrum conductor.eta\" \"metal-Au-eta\" "
                                     "\"spectrum conductor.k\" \"metal-Au-k\" \"float thickness\" 0.05 "
                                     "\"rgb albedo\" [0.1 0.2 0.3] \"float g\" 0.4 \"integer maxdepth\" 7 "
                                     "\"integer nsamples\" 3 \"bool remaproughness\" false\n",
                                 "inline.pbrt");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const PbrtMaterialDesc& d = only_pbrt(s);
  EXPECT_EQ(d.kind, PbrtMaterialKind::CoatedConductor);
  EXPECT_EQ(d.uroughness, 0.1f);
  EXPECT_EQ(d.vroughness, 0.2f);
  EXPECT_EQ(d.eta, 1.4f);
  EXPECT_EQ(d.conductor_uroughness, 0.3f);
  EXPECT_EQ(d.conductor_vroughness, 0.3f);
  const RgbComplexIor au = *named_conductor_ior("Au");
  EXPECT_EQ(d.conductor_eta, au.eta);
  EXPECT_EQ(d.conductor_k, au.k);
  EXPECT_EQ(d.thickness, 0.05f);
  EXPECT_EQ(d.albedo, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(d.g, 0.4f);
  EXPECT_EQ(d.max_depth, 7);
  EXPECT_EQ(d.n_samples, 3);
  EXPECT_FALSE(d.remap_roughness);
  EXPECT_FALSE(d.conductor_by_reflectance);
}

TEST(PbrtMaterials, CoatedConductorDefaultsAndReflectanceMode) {
  const PbrtMaterialDesc def = only_pbrt(parse_pbrt(kHead + "Material \"coatedconductor\"\n", "inline.pbrt"));
  const RgbComplexIor cu = *named_conductor_ior("Cu");  // pbrt's default conductor: copper
  EXPECT_EQ(def.conductor_eta, cu.eta);
  EXPECT_EQ(def.conductor_k, cu.k);
  EXPECT_EQ(def.eta, 1.5f);
  EXPECT_EQ(def.uroughness, 0.0f);
  EXPECT_EQ(def.conductor_uroughness, 0.0f);
  EXPECT_EQ(def.thickness, 0.01f);
  EXPECT_EQ(def.max_depth, 10);
  const PbrtMaterialDesc r = only_pbrt(
      parse_pbrt(kHead + "Material \"coatedconductor\" \"rgb reflectance\" [0.9 0.5 0.2]\n", "inline.pbrt"));
  EXPECT_TRUE(r.conductor_by_reflectance);
  EXPECT_EQ(r.conductor_reflectance.value, Rgb(0.9f, 0.5f, 0.2f));
  const std::string both = error_of(kHead + "Material \"coatedconductor\" \"rgb reflectance\" [0.9 0.5 0.2] "
                                            "\"spectrum conductor.eta\" \"metal-Ag-eta\"\n");
  EXPECT_NE(both.find("inline.pbrt: line 5"), std::string::npos) << both;
  EXPECT_NE(both.find("both \"reflectance\""), std::string::npos) << both;
}

TEST(PbrtMaterials, DiffuseTransmissionAndThinDielectric) {
  const SceneDesc s = parse_pbrt(kHead +
                                     "MakeNamedMaterial \"t\" \"string type\" \"diffusetransmission\" "
                                     "\"rgb reflectance\" [0.3 0.5 0.3] \"rgb transmittance\" [0.5 0.3 0.2] "
                                     "\"float scale\" 2\n"
                                     "MakeNamedMaterial \"d\" \"string type\" \"diffusetransmission\"\n"
                                     "Material \"thindielectric\" \"float eta\" 1.7\n",
                                 "inline.pbrt");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const PbrtMaterialDesc& t = *s.materials[0].pbrt;
  EXPECT_EQ(t.kind, PbrtMaterialKind::DiffuseTransmission);
  EXPECT_EQ(t.reflectance, Rgb(0.3f, 0.5f, 0.3f));
  EXPECT_EQ(t.transmittance, Rgb(0.5f, 0.3f, 0.2f));
  EXPECT_EQ(t.scale, 2.0f);
  EXPECT_EQ(s.materials[1].pbrt->reflectance, Rgb(0.25f));  // pbrt's defaults
  EXPECT_EQ(s.materials[1].pbrt->transmittance, Rgb(0.25f));
  EXPECT_EQ(s.materials[2].pbrt->kind, PbrtMaterialKind::ThinDielectric);
  EXPECT_EQ(s.materials[2].pbrt->eta, 1.7f);
}

TEST(PbrtMaterials, MixesResolveNamesOnceTheFileIsRead) {
  const SceneDesc s = parse_pbrt(kHead +
                                     "MakeNamedMaterial \"red\" \"string type\" \"diffuse\"\n"
                                     "MakeNamedMaterial \"both\" \"string type\" \"mix\" "
                                     "\"string materials\" [\"red\" \"later\"] \"float amount\" 0.4\n"
                                     "Material \"mix\" \"string materials\" [\"both\" \"red\"]\n"
                                     "MakeNamedMaterial \"later\" \"string type\" \"conductor\"\n",
                                 "inline.pbrt");
  ASSERT_EQ(s.materials.size(), 4u);
  ASSERT_TRUE(s.materials[1].mix);
  EXPECT_FALSE(s.materials[1].pbrt);
  EXPECT_EQ(s.materials[1].mix->materials, (std::array<int, 2>{0, 3}));
  EXPECT_EQ(s.materials[1].mix->amount, TexturedFloat(0.4f));
  ASSERT_TRUE(s.materials[2].mix);
  EXPECT_EQ(s.materials[2].mix->materials, (std::array<int, 2>{1, 0}));
  EXPECT_EQ(s.materials[2].mix->amount, TexturedFloat(0.5f));  // pbrt's default
}

TEST(PbrtMaterials, BadMixesNameTheirLine) {
  const std::string missing = error_of(kHead + "MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
                                               "Material \"mix\" \"string materials\" [\"a\" \"nope\"]\n");
  EXPECT_NE(missing.find("inline.pbrt: line 6 (Material \"mix\")"), std::string::npos) << missing;
  EXPECT_NE(missing.find("names \"nope\", which no MakeNamedMaterial defines"), std::string::npos) << missing;
  const std::string cycle =
      error_of(kHead + "MakeNamedMaterial \"d\" \"string type\" \"diffuse\"\n"
                       "MakeNamedMaterial \"a\" \"string type\" \"mix\" \"string materials\" [\"d\" \"b\"]\n"
                       "MakeNamedMaterial \"b\" \"string type\" \"mix\" \"string materials\" [\"a\" \"d\"]\n");
  EXPECT_NE(cycle.find("inline.pbrt: line 6 (MakeNamedMaterial \"a\")"), std::string::npos) << cycle;
  EXPECT_NE(cycle.find("contain each other: \"a\" -> \"b\" -> \"a\""), std::string::npos) << cycle;
  const std::string self = error_of(kHead + "MakeNamedMaterial \"s\" \"string type\" \"mix\" "
                                            "\"string materials\" [\"s\" \"s\"]\n");
  EXPECT_NE(self.find("line 5"), std::string::npos) << self;
  EXPECT_NE(self.find("\"s\" -> \"s\""), std::string::npos) << self;
  const std::string count = error_of(kHead + "Material \"mix\" \"string materials\" [\"a\"]\n");
  EXPECT_NE(count.find("line 5"), std::string::npos) << count;
  EXPECT_NE(count.find("must name two materials, got 1"), std::string::npos) << count;
}

TEST(PbrtMaterials, UnsupportedMaterialsAreWarnedSubstitutions) {
  for (const char* type : {"measured", "hair", "subsurface"}) {
    const SceneDesc s = parse_pbrt(kHead + "Material \"" + type + "\" \"string filename\" \"x.bsdf\"\n", "inline.pbrt");
    ASSERT_FALSE(s.unsupported.empty()) << type;
    EXPECT_NE(s.unsupported.front().find(type), std::string::npos) << type;
    EXPECT_EQ(only_pbrt(s).kind, PbrtMaterialKind::Diffuse) << type;
  }
}

// ---- spectra ----

TEST(PbrtSpectra, EveryNamedSpectrumOfPbrtV4IsKnown) {
  // pbrt-v4's list: 7 glasses, 7 metals (eta and k), 15 standard illuminants and ACES D60, 17 cameras (r, g, b).
  const char* names[] = {"glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5", "glass-F10",
                         "glass-F11", "metal-Ag-eta", "metal-Al-k", "metal-Au-eta", "metal-Cu-k", "metal-CuZn-eta",
                         "metal-MgO-eta", "metal-TiO2-k", "stdillum-A", "stdillum-D50", "stdillum-D65",
                         "stdillum-F1", "stdillum-F12", "illum-acesD60", "canon_eos_100d_r", "nikon_d850_g",
                         "sony_ilce_9_b", "hasselblad_l1d_20c_r"};
  for (const char* n : names) EXPECT_TRUE(named_spectrum(n)) << n;
  EXPECT_EQ(named_spectra_data().size(), 7u + 14u + 16u + 51u);
  for (const NamedSpectrumData& d : named_spectra_data())
    for (SpectrumUse use : {SpectrumUse::Illuminant, SpectrumUse::Albedo, SpectrumUse::Unbounded}) {
      const Rgb c = *named_spectrum_rgb(d.name, use);
      EXPECT_TRUE(c.is_finite() && !c.has_negative()) << d.name;
    }
}

TEST(PbrtSpectra, ReductionsOfKnownValues) {
  // The white point: D65 is RGB 1 as an illuminant, a flat spectrum c is (c, c, c) as a reflectance.
  EXPECT_EQ(*named_spectrum_rgb("stdillum-D65", SpectrumUse::Illuminant), Rgb(1.0f));
  const std::vector<float> l{300, 900}, v{0.3f, 0.3f};
  const Rgb flat = sampled_spectrum_rgb(l, v, SpectrumUse::Albedo);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(flat[c], 0.3f, 1e-5f);
  // BK7's catalogue index n_d = 1.5168 at 587.6 nm; its D65-weighted reduction lies within its dispersion.
  const Rgb bk7 = *named_spectrum_rgb("glass-BK7", SpectrumUse::Unbounded);
  EXPECT_NEAR(bk7.g, 1.5168f, 2e-3f);
  EXPECT_GT(bk7.b, bk7.r);  // normal dispersion: higher index at short wavelengths
  // Illuminant A is a 2856 K blackbody: warm, and near the blackbody's own reduction.
  const Rgb a = *named_spectrum_rgb("stdillum-A", SpectrumUse::Illuminant), bb = *blackbody_rgb(2856.0f);
  EXPECT_GT(a.r, a.b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], bb[c], 0.01f * bb[c] + 1e-3f) << c;
}

TEST(PbrtSpectra, BlackbodyIsNormalisedAsPbrtDoes) {
  // As an illuminant only its chromaticity counts (luminance 1); as a reflectance its peak is 1, as in pbrt-v4.
  for (float kelvin : {1500.0f, 3500.0f, 6500.0f, 12000.0f}) {
    EXPECT_NEAR(blackbody_rgb(kelvin, SpectrumUse::Illuminant)->luminance(), 1.0f, 2e-3f) << kelvin;
    const PiecewiseSpectrum s = *blackbody_spectrum(kelvin);
    float peak = 0.0f;
    for (float v : s.values) peak = std::max(peak, v);
    const float wien = 2.8977721e6f / kelvin;
    if (wien > 361.0f && wien < 829.0f) {
      EXPECT_NEAR(peak, 1.0f, 1e-4f) << kelvin;
    }
    EXPECT_LE(peak, 1.0f + 1e-6f) << kelvin;
    // Its colour as a reflectance: reddish when cool, bluish when hot (a channel may exceed 1 when the spectrum's
    // colour lies outside the sRGB gamut, as in pbrt's RGB film).
    const Rgb albedo = *blackbody_rgb(kelvin, SpectrumUse::Albedo);
    EXPECT_EQ(albedo.r > albedo.b, kelvin < 6000.0f) << kelvin;
  }
  // Through the loader: a blackbody reflectance is the peak-normalised spectrum, not luminance 1.
  const SceneDesc s = parse_pbrt(kHead + "Material \"diffuse\" \"blackbody reflectance\" 3500\n", "inline.pbrt");
  EXPECT_EQ(only_pbrt(s).reflectance, *blackbody_rgb(3500.0f, SpectrumUse::Albedo));
}

TEST(PbrtSpectra, ConductorFitMatchesTheSpectralReflectance) {
  // The fitted (eta, k) reproduce the D65-lit reflectance of the spectral metal over the hemisphere (RMS over angles
  // evenly spaced in projected solid angle) better than eta and k reduced separately, and within 1.5% everywhere
  // except where the spectral colour leaves the gamut (gold's red exceeds 1 at normal incidence, which no Fresnel
  // reflectance reaches).
  for (const char* metal : {"Au", "Cu", "Ag", "Al", "CuZn"}) {
    const PiecewiseSpectrum eta = *named_spectrum(std::string("metal-") + metal + "-eta");
    const PiecewiseSpectrum k = *named_spectrum(std::string("metal-") + metal + "-k");
    const RgbComplexIor fit = conductor_rgb_ior(eta, k);
    const RgbComplexIor separate{spectrum_rgb(eta, SpectrumUse::Unbounded), spectrum_rgb(k, SpectrumUse::Unbounded)};
    Rgb fit_sq(0.0f), separate_sq(0.0f);
    constexpr int kAngles = 32;
    for (int j = 0; j < kAngles; ++j) {
      const float c = std::sqrt((float(j) + 0.5f) / kAngles);
      PiecewiseSpectrum reflectance;
      for (float l = 360; l <= 830; l += 1) {
        reflectance.lambda_nm.push_back(l);
        reflectance.values.push_back(fresnel_conductor(c, eta(l), k(l)));
      }
      const Rgb truth = spectrum_rgb(reflectance, SpectrumUse::Albedo);
      const Rgb fitted = fresnel_conductor(c, fit), apart = fresnel_conductor(c, separate);
      for (int ch = 0; ch < 3; ++ch) {
        fit_sq[ch] += (fitted[ch] - truth[ch]) * (fitted[ch] - truth[ch]) / kAngles;
        separate_sq[ch] += (apart[ch] - truth[ch]) * (apart[ch] - truth[ch]) / kAngles;
        if (truth[ch] < 1.0f) {
          EXPECT_NEAR(fitted[ch], truth[ch], 0.015f) << metal << " cos " << c << " channel " << ch;
        }
      }
    }
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_LE(std::sqrt(fit_sq[ch]), std::sqrt(separate_sq[ch]) + 1e-4f) << metal << " channel " << ch;
  }
}

TEST(PbrtSpectra, UnknownNamesListTheNearestKnownOnes) {
  const std::string e = error_of(kHead + "Material \"dielectric\" \"spectrum eta\" \"glass-F12\"\n");
  EXPECT_NE(e.find("inline.pbrt: line 5 (Material \"dielectric\")"), std::string::npos) << e;
  EXPECT_NE(e.find("\"glass-F12\" is not a named spectrum (nearest: \"glass-F10\", \"glass-F11\""),
            std::string::npos)
      << e;
  EXPECT_EQ(nearest_named_spectra("metal-au-eta", 1).front(), "metal-Au-eta");  // case-insensitive
}

TEST(PbrtSpectra, SpdFilesAreReadRelativeToTheSceneFile) {
  const std::string dir = tmp("spd");
  std::ofstream(dir + "/flat.spd") << "# a flat spectrum\n300 0.4\n900 0.4\n";
  std::ofstream(dir + "/scene.pbrt") << kHead << "Material \"diffuse\" \"spectrum reflectance\" \"flat.spd\"\n";
  const SceneDesc s = load_pbrt(dir + "/scene.pbrt");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(only_pbrt(s).reflectance.value[c], 0.4f, 1e-5f);

  const std::string missing = error_of(kHead + "Material \"diffuse\" \"spectrum reflectance\" \"nope.spd\"\n",
                                       dir + "/other.pbrt");
  EXPECT_NE(missing.find("other.pbrt: line 5"), std::string::npos) << missing;
  EXPECT_NE(missing.find("cannot read the spectrum file"), std::string::npos) << missing;
  fs::create_directories(dir + "/folder.spd");
  const std::string unreadable = error_of(kHead + "Material \"diffuse\" \"spectrum reflectance\" \"folder.spd\"\n",
                                          dir + "/other.pbrt");
  EXPECT_NE(unreadable.find("other.pbrt: line 5"), std::string::npos) << unreadable;
  EXPECT_NE(unreadable.find("cannot read the spectrum file"), std::string::npos) << unreadable;
  std::ofstream(dir + "/bad.spd") << "400 0.5 500\n";
  const std::string odd = error_of(kHead + "Material \"diffuse\" \"spectrum reflectance\" \"bad.spd\"\n",
                                   dir + "/other.pbrt");
  EXPECT_NE(odd.find("line 5"), std::string::npos) << odd;
  EXPECT_NE(odd.find("pairs"), std::string::npos) << odd;
}

}  // namespace
}  // namespace kiln
