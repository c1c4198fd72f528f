// pbrt-v4 textures, bump maps and normal maps as the renderer produces them: a quad seen from above under a distant
// light (maxdepth 1, so every pixel is the Lambertian reflection of that light: albedo / pi * E * cos), rendered
// with the feature on and compared with independent expectations:
//   * a textured reflectance (checkerboard, sRGB imagemap) gives, in every pixel that lies inside one cell or
//     texel, exactly the render of the untextured material with that cell's or texel's reflectance;
//   * a displacement whose height is bilinear in (u, v) bends the rendered shading normal (normal AOV) and the
//     beauty image to the analytic normal of the displaced surface, (-dh/du / |dp/du|, -dh/dv / |dp/dv|, 1)
//     normalised, whose two slopes differ in sign and size;
//   * a normal map that encodes +z leaves the image bit-identical; one that encodes a tilt by 25 degrees towards +u
//     (or +v, or -u) scales the image by cos(angle to the light) / cos(angle of the untilted normal).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "renderer/image_io/image_io.h"
#include "renderer/integrators/aov.h"
#include "renderer/render_util.h"
#include "renderer/texture/scene_textures.h"

namespace kiln::test {
namespace {

constexpr int kRes = 64;

std::string dir() { return tmp_dir("pbrt_texture_render"); }

// A 4 x 4 quad in z = 0 with uv (x + 2, y + 2) / 4, seen from z = 8, lit by a distant light travelling along -light.
std::string quad_scene(const std::string& name, const std::string& world, Vec3f light = {0, 0, 1}) {
  const std::string path = dir() + "/" + name + ".pbrt";
  std::ofstream(path) << "LookAt 0 0 8  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 30\n"
                      << "Film \"rgb\" \"integer xresolution\" " << kRes << " \"integer yresolution\" " << kRes << "\n"
                      << "Integrator \"path\" \"integer maxdepth\" 1\nWorldBegin\n"
                      << "LightSource \"distant\" \"point3 from\" [" << light.x << " " << light.y << " " << light.z
                      << "] \"point3 to\" [0 0 0] \"rgb L\" [2 2 2]\n"
                      << world
                      << "Shape \"trianglemesh\" \"point3 P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0]"
                         " \"point2 uv\" [0 0 1 0 1 1 0 1] \"integer indices\" [0 1 2 0 2 3]\n";
  return path;
}

struct Rendered {
  SceneDesc scene;
  std::unique_ptr<World> world;
  Image image;
  std::vector<Vec3f> normals;  // the normal AOV, per pixel
};

Rendered render(const std::string& path, uint32_t spp = 16) {
  Rendered r;
  r.scene = load_scene(path);
  r.world = build_world(r.scene, {});
  const CameraDesc& cd = r.scene.cameras.at(0);
  const Camera cam(cd);
  Film film(cam.width(), cam.height());
  film.keep_surfaces();  // for the normal AOV
  RenderOptions ro;
  ro.spp_total = spp;
  render_samples(*r.world, cam, scene_settings(cd, r.scene, r.world->features), ro, 0, spp, film);
  r.image = film.mean();
  for (const AovLayer& l : aov_layers(film, kAovNormal))
    for (size_t i = 0; i < l.data.size(); i += 3) r.normals.push_back({l.data[i], l.data[i + 1], l.data[i + 2]});
  return r;
}

// Where the ray through film point (x, y) meets z = 0, as uv of the quad.
Vec2f uv_at(const Camera& cam, float x, float y) {
  const Ray ray = cam.generate_ray(x, y, {0.5f, 0.5f});
  const Vec3f p = ray.o + ray.d * (-ray.o.z / ray.d.z);
  return {(p.x + 2.0f) / 4.0f, (p.y + 2.0f) / 4.0f};
}

// Calls f(x, y, uv at the pixel centre) for every pixel whose footprint, widened by half a pixel, lies in one cell
// of a grid of `cells` x `cells` over the quad's uv square.
template <typename F>
void for_pixels_inside_cells(const CameraDesc& cd, int cells, F&& f) {
  const Camera cam(cd);
  const auto cell = [&](Vec2f uv) { return std::make_pair(int(std::floor(uv.x * cells)), int(std::floor(uv.y * cells))); };
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      const Vec2f c = uv_at(cam, float(x) + 0.5f, float(y) + 0.5f);
      if (c.x <= 0.0f || c.x >= 1.0f || c.y <= 0.0f || c.y >= 1.0f) continue;
      bool inside = true;
      for (float dx : {-0.5f, 1.5f})
        for (float dy : {-0.5f, 1.5f}) inside = inside && cell(uv_at(cam, float(x) + dx, float(y) + dy)) == cell(c);
      if (inside) f(x, y, c);
    }
}

TEST(PbrtTextureRender, CheckerboardReflectanceIsTheUntexturedRenderOfEachCell) {
  const Rendered checks = render(quad_scene(
      "checks", "Texture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4"
                " \"rgb tex1\" [0.8 0.7 0.6] \"rgb tex2\" [0.1 0.2 0.3]\nMaterial \"diffuse\" \"texture reflectance\" \"c\"\n"));
  const Rendered one = render(quad_scene("tex1", "Material \"diffuse\" \"rgb reflectance\" [0.8 0.7 0.6]\n"));
  const Rendered two = render(quad_scene("tex2", "Material \"diffuse\" \"rgb reflectance\" [0.1 0.2 0.3]\n"));
  int checked[2] = {0, 0};
  for_pixels_inside_cells(checks.scene.cameras[0], 4, [&](int x, int y, Vec2f uv) {
    const bool even = (int(std::floor(4 * uv.x)) + int(std::floor(4 * uv.y))) % 2 == 0;
    EXPECT_EQ(checks.image.at(x, y), (even ? one : two).image.at(x, y)) << x << "," << y;
    ++checked[even ? 0 : 1];
  });
  EXPECT_GT(checked[0], 400);
  EXPECT_GT(checked[1], 400);
}

// A mix shades with the component each hit chooses, textured parameters included: with amount 1 every hit takes the
// textured component, and the image is the component's own render, bit for bit (a mix whose component kept its
// untextured placeholder would render the default reflectance instead).
TEST(PbrtTextureRender, AMixResolvesItsTexturedComponentPerHit) {
  const std::string checker =
      "Texture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4"
      " \"rgb tex1\" [0.8 0.7 0.6] \"rgb tex2\" [0.1 0.2 0.3]\n";
  const Rendered direct = render(quad_scene("mix_direct", checker + "Material \"diffuse\" \"texture reflectance\" \"c\"\n"));
  const Rendered mixed = render(quad_scene(
      "mix_textured", checker +
                          "MakeNamedMaterial \"grey\" \"string type\" \"diffuse\"\n"
                          "MakeNamedMaterial \"checks\" \"string type\" \"diffuse\" \"texture reflectance\" \"c\"\n"
                          "Material \"mix\" \"string materials\" [\"grey\" \"checks\"] \"float amount\" 1\n"));
  ASSERT_TRUE(mixed.world->features & kFeatureMix);
  ASSERT_EQ(mixed.image.width(), direct.image.width());
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) ASSERT_EQ(mixed.image.at(x, y), direct.image.at(x, y)) << x << "," << y;
}

// ---- mix with a textured amount: each hit evaluates the amount there, then chooses by the hit's hash ----

// Three diffuse reflectances, distinct in every channel; under the light each pixel is reflectance / pi * 2.
const Rgb kMixA(0.8f, 0.2f, 0.3f), kMixB(0.1f, 0.7f, 0.2f), kMixC(0.3f, 0.1f, 0.9f);
constexpr float kLightL = 2.0f;

std::string rgb_text(Rgb c) {
  std::ostringstream s;
  s << "[" << c.r << " " << c.g << " " << c.b << "]";
  return s.str();
}

// Materials "a", "b" (its reflectance a texture: the component's own textures are evaluated too) and "c", and the
// float textures "checks" (0 on even cells of a 2 x 2 grid over the quad's uv, 1 on odd) and "third" (0.3 everywhere,
// but a texture: a scale texture is not folded into a constant as a constant texture is).
std::string mix_materials() {
  return "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" 2 \"float vscale\" 2"
         " \"float tex1\" 0 \"float tex2\" 1\n"
         "Texture \"third\" \"float\" \"scale\" \"float tex\" 0.6 \"float scale\" 0.5\n"
         "Texture \"b_refl\" \"spectrum\" \"scale\" \"rgb tex\" " + rgb_text(kMixB) + " \"float scale\" 1\n"
         "MakeNamedMaterial \"a\" \"string type\" \"diffuse\" \"rgb reflectance\" " + rgb_text(kMixA) + "\n"
         "MakeNamedMaterial \"b\" \"string type\" \"diffuse\" \"texture reflectance\" \"b_refl\"\n"
         "MakeNamedMaterial \"c\" \"string type\" \"diffuse\" \"rgb reflectance\" " + rgb_text(kMixC) + "\n";
}

// The closed form of a pixel whose samples shade with a, b, c with probabilities w (maxdepth 1 under the distant
// light straight above: reflectance / pi * L, the same for every sample), and the standard error of the mean of n
// such samples (each sample is one of the three values).
struct MixExpectation {
  Rgb mean, sigma;
};
MixExpectation mix_expectation(std::array<double, 3> w, double n) {
  MixExpectation e{Rgb(0.0f), Rgb(0.0f)};
  const std::array<Rgb, 3> r = {kMixA, kMixB, kMixC};
  for (int ch = 0; ch < 3; ++ch) {
    double m = 0, m2 = 0;
    for (int i = 0; i < 3; ++i) {
      const double v = double(r[size_t(i)][ch]) * kLightL / kPi;
      m += w[size_t(i)] * v;
      m2 += w[size_t(i)] * v * v;
    }
    e.mean[ch] = float(m);
    e.sigma[ch] = float(std::sqrt(std::max(m2 - m * m, 0.0) / n));
  }
  return e;
}

// Mean of the pixels inside the cells of the 2 x 2 grid, even cells (0) and odd ones (1), and their counts.
struct CellMeans {
  std::array<Rgb, 2> mean{Rgb(0.0f), Rgb(0.0f)};
  std::array<int, 2> pixels{0, 0};
};
CellMeans cell_means(const Rendered& r) {
  CellMeans m;
  std::array<std::array<double, 3>, 2> sum{};
  for_pixels_inside_cells(r.scene.cameras[0], 2, [&](int x, int y, Vec2f uv) {
    const int odd = (int(std::floor(2 * uv.x)) + int(std::floor(2 * uv.y))) % 2;
    for (int ch = 0; ch < 3; ++ch) sum[size_t(odd)][size_t(ch)] += r.image.at(x, y)[ch];
    ++m.pixels[size_t(odd)];
  });
  for (int odd = 0; odd < 2; ++odd)
    for (int ch = 0; ch < 3; ++ch) m.mean[size_t(odd)][ch] = float(sum[size_t(odd)][size_t(ch)] / m.pixels[size_t(odd)]);
  return m;
}

// Within 4 standard errors of the closed form (and float rounding).
void expect_blend(Rgb got, const MixExpectation& e, const std::string& what) {
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_NEAR(got[ch], e.mean[ch], 4.0f * e.sigma[ch] + 1e-5f) << what << ", channel " << ch;
}

constexpr uint32_t kMixSpp = 16;

// An amount of 0 on even cells and 1 on odd ones: every pixel inside a cell is that cell's material, exactly its
// closed form; an amount of 0.3 everywhere (a texture): the blend 0.7 a + 0.3 b in expectation, and a visible
// per-hit choice (pixels differ, where a blend of the materials would make them all equal).
TEST(PbrtTextureRender, MixWithATexturedAmountChoosesPerHit) {
  const Rendered halves = render(quad_scene(
      "mix_amount_checks", mix_materials() + "Material \"mix\" \"string materials\" [\"a\" \"b\"] \"texture amount\" \"checks\"\n"), kMixSpp);
  ASSERT_TRUE(halves.scene.materials.back().mix->amount.textured());
  const CellMeans cells = cell_means(halves);
  ASSERT_GT(cells.pixels[0], 400);
  ASSERT_GT(cells.pixels[1], 400);
  int wrong = 0;
  std::string first_wrong;
  for_pixels_inside_cells(halves.scene.cameras[0], 2, [&](int x, int y, Vec2f uv) {
    const bool odd = (int(std::floor(2 * uv.x)) + int(std::floor(2 * uv.y))) % 2 == 1;
    const Rgb want = mix_expectation(odd ? std::array<double, 3>{0, 1, 0} : std::array<double, 3>{1, 0, 0}, 1).mean;
    const Rgb got = halves.image.at(x, y);
    if (std::max({std::fabs(got.r - want.r), std::fabs(got.g - want.g), std::fabs(got.b - want.b)}) <= 1e-5f) return;
    if (wrong++ == 0)
      first_wrong = std::to_string(x) + "," + std::to_string(y) + ": " + rgb_text(got) + " instead of " + rgb_text(want);
  });
  EXPECT_EQ(wrong, 0) << "pixels off their cell's material, the first " << first_wrong;

  const Rendered third = render(quad_scene(
      "mix_amount_third", mix_materials() + "Material \"mix\" \"string materials\" [\"a\" \"b\"] \"texture amount\" \"third\"\n"), kMixSpp);
  ASSERT_TRUE(third.scene.materials.back().mix->amount.textured());
  const CellMeans blend = cell_means(third);
  const int pixels = blend.pixels[0] + blend.pixels[1];
  const Rgb mean = (blend.mean[0] * float(blend.pixels[0]) + blend.mean[1] * float(blend.pixels[1])) / float(pixels);
  expect_blend(mean, mix_expectation({0.7, 0.3, 0.0}, double(pixels) * kMixSpp), "amount 0.3");
  int differ = 0;
  for_pixels_inside_cells(third.scene.cameras[0], 2, [&](int x, int y, Vec2f) {
    differ += third.image.at(x, y) != third.image.at(kRes / 2, kRes / 2);
  });
  EXPECT_GT(differ, pixels / 2);
}

// The same seed gives the same image whatever the thread count: the choice is a function of the hit.
TEST(PbrtTextureRender, MixWithATexturedAmountIsDeterministic) {
  const SceneDesc scene = load_scene(quad_scene(
      "mix_amount_threads", mix_materials() + "Material \"mix\" \"string materials\" [\"a\" \"b\"] \"texture amount\" \"third\"\n"));
  const auto world = build_world(scene, {});
  const CameraDesc& cd = scene.cameras[0];
  const IntegratorSettings s = scene_settings(cd, scene, world->features);
  const Image one = render_image(*world, cd, s, 4, 7, 1);
  const Image two = render_image(*world, cd, s, 4, 7, 2, true);
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) ASSERT_EQ(one.at(x, y), two.at(x, y)) << x << "," << y;
}

// A mix whose component is a mix with a textured amount: the outer mix takes c with probability 0.25 (a constant,
// chosen when the hit is made, or a texture, chosen with the inner one), else the inner mix, whose amount (0 on
// even cells, 1 on odd ones) gives a on even cells and b on odd ones.
TEST(PbrtTextureRender, NestedMixWithATexturedInnerAmount) {
  for (const char* outer_amount : {"\"float amount\" 0.75", "\"texture amount\" \"three_quarters\""}) {
    const Rendered r = render(quad_scene(
        "mix_amount_nested", mix_materials() +
            "Texture \"three_quarters\" \"float\" \"scale\" \"float tex\" 1.5 \"float scale\" 0.5\n"
            "MakeNamedMaterial \"inner\" \"string type\" \"mix\" \"string materials\" [\"a\" \"b\"] \"texture amount\" \"checks\"\n"
            "Material \"mix\" \"string materials\" [\"c\" \"inner\"] " + outer_amount + "\n"), kMixSpp);
    const CellMeans cells = cell_means(r);
    expect_blend(cells.mean[0], mix_expectation({0.75, 0.0, 0.25}, double(cells.pixels[0]) * kMixSpp),
                 std::string(outer_amount) + ", even cells");
    expect_blend(cells.mean[1], mix_expectation({0.0, 0.75, 0.25}, double(cells.pixels[1]) * kMixSpp),
                 std::string(outer_amount) + ", odd cells");
  }
}

// An 8-bit sRGB PNG of 4 x 4 distinct texels (point filtered): each pixel inside a texel is the white render times
// the texel's decoded value, with row 0 of the file at the top of the uv square (v = 1).
TEST(PbrtTextureRender, ImagemapReflectanceIsTheDecodedTexelWithVUp) {
  std::vector<uint8_t> rgb;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) rgb.insert(rgb.end(), {uint8_t(40 + 60 * x), uint8_t(30 + 70 * y), uint8_t(200)});
  write_png(dir() + "/texels.png", rgb, 4, 4);
  const Rendered tex = render(quad_scene(
      "imagemap", "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"texels.png\" \"string filter\" \"point\"\n"
                  "Material \"diffuse\" \"texture reflectance\" \"t\"\n"));
  const Rendered white = render(quad_scene("white", "Material \"diffuse\" \"rgb reflectance\" [1 1 1]\n"));
  const auto decode = [](int v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  int checked = 0;
  for_pixels_inside_cells(tex.scene.cameras[0], 4, [&](int x, int y, Vec2f uv) {
    const int tx = int(std::floor(4 * uv.x)), ty = 3 - int(std::floor(4 * uv.y));
    const Rgb w = white.image.at(x, y), t = tex.image.at(x, y);
    EXPECT_NEAR(t.r, w.r * decode(40 + 60 * tx), 2e-6 * w.r) << x << "," << y;
    EXPECT_NEAR(t.g, w.g * decode(30 + 70 * ty), 2e-6 * w.g) << x << "," << y;
    EXPECT_NEAR(t.b, w.b * decode(200), 2e-6 * w.b) << x << "," << y;
    ++checked;
  });
  EXPECT_GT(checked, 1000);
}

// h(u, v) bilinear: v00 = 0, v10 = 0.8, v01 = -0.5, v11 = 0.6 (so dh/du > 0 and dh/dv < 0 everywhere).
constexpr float kH00 = 0.0f, kH10 = 0.8f, kH01 = -0.5f, kH11 = 0.6f;
const char* kBump = "Texture \"h\" \"float\" \"bilerp\" \"float v00\" 0 \"float v10\" 0.8 \"float v01\" -0.5"
                    " \"float v11\" 0.6\nMaterial \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]"
                    " \"texture displacement\" \"h\"\n";

Vec3f analytic_bump_normal(Vec2f uv) {
  const float dhdu = (1 - uv.y) * (kH10 - kH00) + uv.y * (kH11 - kH01);
  const float dhdv = (1 - uv.x) * (kH01 - kH00) + uv.x * (kH11 - kH10);
  return normalize(Vec3f(-dhdu / 4.0f, -dhdv / 4.0f, 1.0f));  // |dp/du| = |dp/dv| = 4
}

TEST(PbrtTextureRender, BumpMapGivesTheDisplacedSurfacesNormal) {
  const Vec3f light = normalize(Vec3f(1, 2, 4));
  const Rendered bumped = render(quad_scene("bump", kBump, light));
  const Rendered flat = render(quad_scene("flat", "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n", light));
  int checked = 0;
  for_pixels_inside_cells(bumped.scene.cameras[0], 1, [&](int x, int y, Vec2f uv) {
    const Vec3f n = analytic_bump_normal(uv);
    const Vec3f aov = bumped.normals[size_t(y * kRes + x)];
    EXPECT_NEAR(aov.x, n.x, 2e-3f) << x << "," << y;
    EXPECT_NEAR(aov.y, n.y, 2e-3f) << x << "," << y;
    EXPECT_NEAR(aov.z, n.z, 2e-3f) << x << "," << y;
    // The flat render's cosine is light.z: the bumped one's is n . light.
    const float expected = flat.image.at(x, y).g * dot(n, light) / light.z;
    EXPECT_NEAR(bumped.image.at(x, y).g, expected, 3e-3f * expected) << x << "," << y;
    ++checked;
  });
  EXPECT_GT(checked, 2000);
}

// An 8 x 8 float normal map of four 4 x 4 blocks: top left (v > 1/2, u < 1/2) tilted by 25 degrees towards +u,
// top right towards +v, bottom left +z, bottom right towards -u.
std::string write_normal_map(const std::string& name, bool tilted) {
  const float s = std::sin(radians(25.0f)), c = std::cos(radians(25.0f));
  const Vec3f block[2][2] = {{{s, 0, c}, {0, s, c}}, {{0, 0, 1}, {-s, 0, c}}};  // [row][column]
  Image img(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const Vec3f n = tilted ? block[y / 4][x / 4] : Vec3f(0, 0, 1);
      img.at(x, y) = Rgb((n.x + 1) / 2, (n.y + 1) / 2, (n.z + 1) / 2);
    }
  write_exr(dir() + "/" + name, img, {}, {});
  return name;
}

TEST(PbrtTextureRender, NormalMapTiltsTheNormalByTheEncodedAngle) {
  const Vec3f light = normalize(Vec3f(std::sin(radians(40.0f)), std::sin(radians(40.0f)), 1.0f));
  const std::string diffuse = "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]";
  const Rendered plain = render(quad_scene("plain", diffuse + "\n", light));
  const Rendered up = render(quad_scene(
      "up", diffuse + " \"string normalmap\" \"" + write_normal_map("up.exr", false) + "\"\n", light));
  const Rendered tilted = render(quad_scene(
      "tilted", diffuse + " \"string normalmap\" \"" + write_normal_map("tilted.exr", true) + "\"\n", light));
  // +z everywhere: the same image, bit for bit.
  EXPECT_EQ(up.image.pixels(), plain.image.pixels());
  const float s = std::sin(radians(25.0f)), c = std::cos(radians(25.0f));
  int checked = 0;
  for_pixels_inside_cells(tilted.scene.cameras[0], 2, [&](int x, int y, Vec2f uv) {
    // Away from the bilinear seams between blocks, in the middle and across the repeated edges.
    const auto near_seam = [](float t) { return std::fabs(t - 0.5f) < 0.1f || t < 0.1f || t > 0.9f; };
    if (near_seam(uv.x) || near_seam(uv.y)) return;
    const bool top = uv.y > 0.5f, left = uv.x < 0.5f;
    const Vec3f n = top ? (left ? Vec3f(s, 0, c) : Vec3f(0, s, c)) : (left ? Vec3f(0, 0, 1) : Vec3f(-s, 0, c));
    const float expected = plain.image.at(x, y).g * dot(n, light) / light.z;
    EXPECT_NEAR(tilted.image.at(x, y).g, expected, 1e-4f * expected) << x << "," << y;
    const Vec3f aov = tilted.normals[size_t(y * kRes + x)];
    EXPECT_NEAR(dot(aov, n), 1.0f, 1e-5f) << x << "," << y;
    ++checked;
  });
  EXPECT_GT(checked, 1000);
}

// A texture only an unused material names is never compiled: no texture system, no image opened.
TEST(PbrtTextureRender, TexturesOfUnusedMaterialsCostNothing) {
  write_png(dir() + "/unused.png", {1, 2, 3}, 1, 1);
  const Rendered r = render(quad_scene(
      "unused", "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"unused.png\"\n"
                "MakeNamedMaterial \"never\" \"string type\" \"diffuse\" \"texture reflectance\" \"t\"\n"
                "Material \"diffuse\"\n"), 1);
  EXPECT_FALSE(r.world->textures);
  EXPECT_FALSE(r.world->features & kFeatureTextures);
  const Rendered used = render(quad_scene(
      "used", "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"unused.png\"\n"
              "Texture \"n\" \"float\" \"fbm\"\nMaterial \"diffuse\" \"texture reflectance\" \"t\"\n"), 1);
  ASSERT_TRUE(used.world->textures);
  const TextureBuildStats st = used.world->textures->stats();
  EXPECT_TRUE(st.texture_system_built);
  EXPECT_EQ(st.pbrt.defined, 2u);
  EXPECT_EQ(st.pbrt.compiled, 1u);
  EXPECT_EQ(st.pbrt.images, 1u);
  EXPECT_EQ(st.textured_materials, 1u);
}

}  // namespace
}  // namespace kiln::test
