// Textures (renderer/texture/): image lookups through the OpenImageIO plugin against the texels of small files
// written here, bump and normal maps against analytic tilts, and a constant texture against the untextured material
// under every integrator. (The Perlin noise is tested in tests/core/perlin_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"
#include "renderer/texture/scene_textures.h"

namespace kiln::test {
namespace {

SceneDesc scene_with_texture(TextureDesc t) {
  SceneDesc s;
  s.source_path = "test.xml";
  t.name = "Texture id=1";
  s.textures.push_back(std::move(t));
  return s;
}

TextureDesc image_texture(const std::string& path, TextureFilter filter, TextureWrap wrap = TextureWrap::Repeat) {
  TextureDesc t;
  t.source = TextureSource::Image;
  t.image_path = path;
  t.filter = filter;
  t.wrap = wrap;
  return t;
}

Rgb texel(int x, int y) { return Rgb(float(x), float(y), float(10 * x + y)); }

// Texel centre (x + 1/2) / W, (y + 1/2) / H: s to the right, t down the image.
Vec2f centre(int x, int y, int w, int h) { return {(float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h)}; }

TEST(TextureLookup, NearestReturnsTheTexel) {
  const std::string path = write_test_exr("grid.exr", 4, 3, texel);
  const SceneDesc s = scene_with_texture(image_texture(path, TextureFilter::Nearest));
  const SceneTextures tex(s, {});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(tex.value(0, centre(x, y, 4, 3), {}), texel(x, y)) << x << "," << y;
      // Anywhere inside the texel, not only at its centre.
      const Vec2f off = centre(x, y, 4, 3) + Vec2f(0.2f / 4, -0.3f / 3);
      EXPECT_EQ(tex.value(0, off, {}), texel(x, y)) << x << "," << y;
    }
}

TEST(TextureLookup, BilinearMixesTheFourNearestTexels) {
  const std::string path = write_test_exr("grid_bilinear.exr", 4, 3, texel);
  const SceneDesc s = scene_with_texture(image_texture(path, TextureFilter::Bilinear));
  const SceneTextures tex(s, {});
  // Between the centres of texels (1,0), (2,0), (1,1), (2,1) at fractions fx, fy.
  const float fx = 0.25f, fy = 0.75f;
  const Vec2f uv((1.5f + fx) / 4.0f, (0.5f + fy) / 3.0f);
  const Rgb expected = texel(1, 0) * ((1 - fx) * (1 - fy)) + texel(2, 0) * (fx * (1 - fy)) +
                       texel(1, 1) * ((1 - fx) * fy) + texel(2, 1) * (fx * fy);
  const Rgb got = tex.value(0, uv, {});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-4f) << c;
}

TEST(TextureLookup, RepeatWrapsAndClampHoldsTheEdge) {
  const std::string path = write_test_exr("grid_wrap.exr", 4, 3, texel);
  const SceneDesc rs = scene_with_texture(image_texture(path, TextureFilter::Nearest, TextureWrap::Repeat));
  const SceneDesc cs = scene_with_texture(image_texture(path, TextureFilter::Nearest, TextureWrap::Clamp));
  const SceneTextures repeat(rs, {}), clamp(cs, {});
  const Vec2f left_of_0 = centre(0, 1, 4, 3) - Vec2f(1.0f / 4, 0);  // one texel left of column 0
  EXPECT_EQ(repeat.value(0, left_of_0, {}), texel(3, 1));
  EXPECT_EQ(clamp.value(0, left_of_0, {}), texel(0, 1));
  EXPECT_EQ(repeat.value(0, centre(2, 2, 4, 3) + Vec2f(3, -2), {}), texel(2, 2));
}

// An 8-bit PNG: texel values come back as file values / Normalizer (default: the format's 255), then degamma.
TEST(TextureLookup, NormalizerAndDegammaOfAnEightBitImage) {
  const std::string path = tmp_dir("textures") + "/eight_bit.png";
  write_png(path, {51, 102, 255, 0, 0, 0}, 2, 1);
  TextureDesc d = image_texture(path, TextureFilter::Nearest);
  const SceneDesc def = scene_with_texture(d);
  d.normalizer = 1.0f;
  const SceneDesc raw = scene_with_texture(d);
  d.normalizer = 255.0f;
  d.degamma = true;
  const SceneDesc dg = scene_with_texture(d);
  const Vec2f uv = centre(0, 0, 2, 1);
  const Rgb a = SceneTextures(def, {}).value(0, uv, {}), b = SceneTextures(raw, {}).value(0, uv, {}),
            c = SceneTextures(dg, {}).value(0, uv, {});
  EXPECT_NEAR(a.r, 0.2f, 1e-6f);
  EXPECT_NEAR(a.g, 0.4f, 1e-6f);
  EXPECT_NEAR(b.g, 102.0f, 1e-4f);
  EXPECT_NEAR(c.g, std::pow(0.4f, 2.2f), 1e-6f);
}

// ---- bump and normal maps ----------------------------------------------------------------------------------------

TEST(BumpMap, ConstantHeightLeavesTheNormal) {
  const std::string path = write_test_exr("flat.exr", 16, 16, [](int, int) { return Rgb(0.7f); });
  TextureDesc d = image_texture(path, TextureFilter::Bilinear);
  d.bump = true;
  d.bump_factor = 30.0f;
  const SceneDesc s = scene_with_texture(d);
  const SceneTextures tex(s, {});
  const Vec3f n(0, 0, 1);
  for (const Vec2f uv : {Vec2f(0.31f, 0.62f), Vec2f(0.5f, 0.5f), Vec2f(0.97f, 0.03f)}) {
    const Vec3f b = tex.bumped_normal(tex.textures()[0], n, uv, {}, {2, 0, 0}, {0, 3, 0});
    EXPECT_EQ(b, n);
  }
}

// Height h = c x (texel column x): one texel further along u the height grows by c, so the normal tilts against
// dp/du by atan(BumpFactor * c).
TEST(BumpMap, LinearRampTiltsByTheExpectedAngle) {
  const float c = 0.01f;
  const std::string path = write_test_exr("ramp.exr", 32, 8, [&](int x, int) { return Rgb(c * float(x)); });
  for (const float k : {1.0f, 30.0f}) {
    TextureDesc d = image_texture(path, TextureFilter::Bilinear);
    d.bump = true;
    d.bump_factor = k;
    const SceneDesc s = scene_with_texture(d);
    const SceneTextures tex(s, {});
    const Vec3f n(0, 0, 1), dpdu(5, 0, 0), dpdv(0, 5, 0);
    const Vec3f b = tex.bumped_normal(tex.textures()[0], n, centre(13, 4, 32, 8), {}, dpdu, dpdv);
    EXPECT_NEAR(angle_between(b, n), std::atan(k * c), 1e-5f) << k;
    EXPECT_LT(b.x, 0.0f) << "the normal leans away from rising height";
    EXPECT_NEAR(b.y, 0.0f, 1e-6f);
  }
}

// Height h = c x + 2 c y (texel column x, row y; t and so v run down the image): the normal tilts against the unit
// tangent along dp/du by c and against the unit bitangent on dp/dv's side by 2c, per unit of BumpFactor:
// n' = normalize(n - k (c t + 2c b)). With dp/dv flipped, b flips and the v tilt turns the other way.
TEST(BumpMap, RampAlongBothAxesTiltsAgainstTangentAndBitangent) {
  const float c = 0.01f, k = 20.0f;
  const std::string path =
      write_test_exr("ramp_uv.exr", 32, 16, [&](int x, int y) { return Rgb(c * float(x) + 2.0f * c * float(y)); });
  TextureDesc d = image_texture(path, TextureFilter::Bilinear);
  d.bump = true;
  d.bump_factor = k;
  const SceneDesc s = scene_with_texture(d);
  const SceneTextures tex(s, {});
  const Vec3f n(0, 0, 1), dpdu(4, 0, 0);
  for (const float v_sign : {1.0f, -1.0f}) {
    const Vec3f dpdv(0, 3 * v_sign, 0);
    const Vec3f b = tex.bumped_normal(tex.textures()[0], n, centre(13, 7, 32, 16), {}, dpdu, dpdv);
    const Vec3f expected = normalize(Vec3f(-k * c, -2 * k * c * v_sign, 1));
    EXPECT_NEAR(angle_between(b, expected), 0.0f, 1e-4f)
        << "dp/dv sign " << v_sign << ": got " << b.x << " " << b.y << " " << b.z;
  }
}

// Texel c encodes the tangent-space normal 2c - 1 (x along the unit tangent t from dp/du, y along n x t, z along n):
// a flat texel keeps n, tilted ones turn it towards t and towards n x t by the encoded amounts. Along the tangent
// exactly (90 degrees) the result is clamped back to n (a normal cannot leave the surface's side).
TEST(NormalMap, TexelsTurnTheNormalByTheirEncodedTangentSpaceVector) {
  const Rgb texels[] = {Rgb(0.5f, 0.5f, 1.0f), Rgb(0.75f, 0.5f, 0.9f), Rgb(0.5f, 0.25f, 0.9f), Rgb(1.0f, 0.5f, 0.5f)};
  const std::string path = write_test_exr("normal.exr", 4, 1, [&](int x, int) { return texels[x]; });
  TextureDesc d = image_texture(path, TextureFilter::Nearest);
  d.decal = DecalMode::ReplaceNormal;
  const SceneDesc s = scene_with_texture(d);
  const SceneTextures tex(s, {});
  const Vec3f n = normalize(Vec3f(0, 1, 1));
  const Vec3f dpdu(1, 0.4f, -0.4f);  // not perpendicular to n: the tangent is its projection
  const Vec3f t = normalize(dpdu - n * dot(dpdu, n)), b = cross(n, t);
  const Vec3f expected[] = {n, normalize(t * 0.5f + n * 0.8f), normalize(b * -0.5f + n * 0.8f), n};
  for (int x = 0; x < 4; ++x) {
    const Vec3f m = tex.mapped_normal(tex.textures()[0], n, centre(x, 0, 4, 1), {}, dpdu);
    EXPECT_NEAR(angle_between(m, expected[x]), 0.0f, 1e-3f) << "texel " << x << ": " << m.x << " " << m.y << " " << m.z;
  }
}

// ---- a constant texture equals the untextured material -------------------------------------------------------------

// A grey floor and a sphere under a point light; kd of the sphere from the material or from a constant texture.
SceneDesc constant_scene(std::optional<std::string> texture_path, RendererKind renderer, SceneRules rules) {
  SceneDesc s = load_scene(std::string(KILN_SOURCE_DIR) + "/scenes/default.xml");
  s.rules = rules;
  for (CameraDesc& c : s.cameras) {
    c.width = c.height = 24;
    c.renderer = renderer;
    c.pt = PathTracingFlags{true, true, false};
  }
  const Rgb kd(0.5f, 0.25f, 0.75f);
  for (MaterialDesc& m : s.materials) m.diffuse = kd;
  if (texture_path) {
    TextureDesc t = image_texture(*texture_path, TextureFilter::Nearest);
    t.name = "Texture id=1";
    s.textures.push_back(t);
    for (MaterialDesc& m : s.materials) m.diffuse = Rgb(0.9f, 0.1f, 0.3f);  // replaced by the texture
    for (MeshDesc& m : s.meshes) m.textures = {0};
    for (SphereDesc& sp : s.spheres) sp.textures = {0};
  }
  return s;
}

TEST(ConstantTexture, EqualsTheUntexturedMaterialUnderEveryIntegrator) {
  const std::string path = write_test_exr("constant.exr", 8, 8, [](int, int) { return Rgb(0.5f, 0.25f, 0.75f); });
  const std::pair<RendererKind, SceneRules> cases[] = {{RendererKind::PathTracing, SceneRules::Kiln},
                                                       {RendererKind::PathTracing, SceneRules::Ceng795Course},
                                                       {RendererKind::RayTracing, SceneRules::Ceng795Course}};
  for (const auto& [renderer, rules] : cases) {
    const SceneDesc plain = constant_scene(std::nullopt, renderer, rules);
    const SceneDesc textured = constant_scene(path, renderer, rules);
    const auto wp = build_scene_world(plain), wt = build_scene_world(textured);
    ASSERT_TRUE(wt->textures);
    ASSERT_FALSE(wp->textures);
    const IntegratorSettings sp = scene_settings(plain.cameras[0], plain, wp->features);
    const IntegratorSettings st = scene_settings(textured.cameras[0], textured, wt->features);
    const Image a = render_image(*wp, plain.cameras[0], sp, 16, 3);
    const Image b = render_image(*wt, textured.cameras[0], st, 16, 3);
    double sum = 0;
    size_t differ = 0;
    for (size_t i = 0; i < a.pixels().size(); ++i) {
      sum += a.pixels()[i].luminance();
      if (!(a.pixels()[i] == b.pixels()[i])) ++differ;
    }
    EXPECT_GT(sum, 0.0) << sp.describe();
    EXPECT_EQ(differ, 0u) << sp.describe();
  }
}

// The consuming world build moves a mesh's arrays out of the description: its uv must survive the move.
TEST(TexturedWorld, ConsumedMeshKeepsItsTextureCoordinates) {
  SceneDesc s;
  s.source_path = "test.xml";
  MaterialDesc m;
  m.diffuse = Rgb(0.5f);
  s.materials.push_back(m);
  TextureDesc t;
  t.source = TextureSource::Checkerboard;
  t.name = "Texture id=1";
  s.textures.push_back(t);
  MeshDesc mesh;
  mesh.name = "Mesh id=1";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.uvs = {{0.1f, 0.2f}, {0.9f, 0.2f}, {0.1f, 0.8f}};
  mesh.indices = {0, 1, 2};
  mesh.material = 0;
  mesh.textures = {0};
  s.meshes.push_back(mesh);
  WorldOptions wo;
  wo.build_accelerator = false;
  const auto w = build_world_taking_meshes(s, wo);
  ASSERT_EQ(w->shape_data.size(), 1u);
  ASSERT_GE(w->shape_data[0].textures, 0);
  ASSERT_GE(w->shape_data[0].uvs, 0);
  EXPECT_EQ(w->uvs[size_t(w->shape_data[0].uvs)][1].x, 0.9f);
}

TEST(TexturedWorld, NoTextureSystemWithoutTexturesNorWithOnlyProceduralOnes) {
  SceneDesc s = load_scene(std::string(KILN_SOURCE_DIR) + "/scenes/default.xml");
  EXPECT_FALSE(build_scene_world(s)->textures);
  TextureDesc t;
  t.source = TextureSource::Perlin;
  t.name = "Texture id=1";
  s.textures.push_back(t);
  for (SphereDesc& sp : s.spheres) sp.textures = {0};
  const auto w = build_scene_world(s);
  ASSERT_TRUE(w->textures);
  EXPECT_FALSE(w->textures->stats().texture_system_built);
  EXPECT_EQ(w->textures->stats().procedural, 1u);
}

}  // namespace
}  // namespace kiln::test
