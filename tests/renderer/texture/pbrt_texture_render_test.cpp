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

#include <cmath>
#include <fstream>

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
