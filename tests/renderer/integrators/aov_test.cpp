// AOVs from the sample loop (renderer/integrators/aov.h): what each camera sample sees, recorded by the integrators
// after the hit's textures, bump and normal maps are applied, and filtered by the film like the colour. Checked on
// scenes whose AOVs are known in closed form: a plane with a texture of four colours, a plane with a bump ramp, a
// replace_all texture whose albedo is the very colour the image shows, and a mirror the AOVs look through.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "renderer/image_io/image_io.h"
#include "renderer/integrators/aov.h"
#include "renderer/render_util.h"
#include "tests/support/shared_data.h"

namespace kiln::test {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kRes = 32;

// A camera at the origin looking down -z (FovY 90) at the plane z = -2, which fills the view, with uv (0, 0) at its
// top left corner and (1, 1) at its bottom right (u along +x, v along -y, as an image's rows run). The plane spans
// [-2, 2]^2 of it in view, so uv spans [0.25, 0.75]^2. `texture` is the XML of texture 1 (empty: untextured).
SceneDesc textured_plane(const std::string& texture, const char* rules) {
  const std::string dir = tmp_dir("aov_scenes");
  const std::string path = dir + "/plane_" + std::to_string(std::hash<std::string>{}(texture + rules)) + ".xml";
  std::ofstream(path) << R"(<Scene rules=")" << rules << R"(">
  <MaxRecursionDepth>2</MaxRecursionDepth>
  <BackgroundColor>0 0 0</BackgroundColor>
  <Cameras><Camera id="1" type="lookAt"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
    <FovY>90</FovY><NearDistance>1</NearDistance><ImageResolution>)"
                      << kRes << " " << kRes << R"(</ImageResolution>
    <ImageName>plane.exr</ImageName></Camera></Cameras>
  <Lights><PointLight id="1"><Position>0.3 0.2 -1</Position><Intensity>5 5 5</Intensity></PointLight></Lights>
  <Materials><Material id="1"><AmbientReflectance>0 0 0</AmbientReflectance>
    <DiffuseReflectance>0.1 0.2 0.3</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance>
  </Material></Materials>
  <Textures>)" << texture << R"(</Textures>
  <VertexData>-4 4 -2 4 4 -2 4 -4 -2 -4 -4 -2</VertexData>
  <TexCoordData>0 0 1 0 1 1 0 1</TexCoordData>
  <Objects><Mesh id="1"><Material>1</Material>)"
                      << (texture.empty() ? "" : "<Texture>1</Texture>") << R"(<Faces>1 3 2 1 4 3</Faces></Mesh></Objects>
</Scene>
)";
  return load_scene(path);
}

// Renders camera 0 with the film keeping what the samples see.
Film render_film(const SceneDesc& scene, const IntegratorSettings& settings, uint32_t spp, uint64_t seed = 5) {
  const auto world = build_scene_world(scene);
  IntegratorSettings s = settings;
  s.features = world->features;
  const Camera cam(scene.cameras[0]);
  Film film(cam.width(), cam.height());
  film.keep_surfaces();
  RenderOptions ro;
  ro.seed = seed;
  ro.spp_total = spp;
  render_samples(*world, cam, s, ro, 0, spp, film);
  return film;
}

std::vector<std::pair<const char*, IntegratorSettings>> every_integrator() {
  CoursePathSettings course_path;
  course_path.nee = true;
  return {{"kiln", IntegratorSettings{PathSettings{}}},
          {"course path", IntegratorSettings{course_path}},
          {"course rays", IntegratorSettings{CourseRaySettings{}}}};
}

// Pixels whose samples all land inside one texel-quadrant of the plane: away from the centre lines by a pixel.
bool inside_a_quadrant(int x, int y) { return std::abs(2 * x + 1 - kRes) > 2 && std::abs(2 * y + 1 - kRes) > 2; }

// A 2 x 2 texture (nearest) over uv [0, 1]^2 puts one texel in each quadrant of the view: the albedo of every
// sample there is the Lambertian reflectance pi kd of kd = that texel (the course's DiffuseReflectance is a radiance
// factor, renderer/integrators/aov.h), not the material's own kd, under every integrator.
TEST(Aov, AlbedoIsTheTexturedReflectance) {
  const Rgb texels[2][2] = {{Rgb(0.05f, 0.1f, 0.2f), Rgb(0.2f, 0.05f, 0.1f)},
                            {Rgb(0.1f, 0.2f, 0.05f), Rgb(0.15f, 0.15f, 0.02f)}};
  const std::string image = write_test_exr("quadrants.exr", 2, 2, [&](int x, int y) { return texels[y][x]; });
  const std::string texture = R"(<Texture id="1"><ImageName>)" + image +
                              R"(</ImageName><Interpolation>nearest</Interpolation><DecalMode>replace_kd</DecalMode>
    <Normalizer>1</Normalizer></Texture>)";
  const SceneDesc scene = textured_plane(texture, "kiln");
  for (const auto& [name, settings] : every_integrator()) {
    SCOPED_TRACE(name);
    const Film film = render_film(scene, settings, 4);
    int checked = 0;
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) {
        if (!inside_a_quadrant(x, y)) continue;
        const Rgb want = texels[2 * y / kRes][2 * x / kRes] * kPi;
        const Rgb got = film.surface_mean(x, y).albedo;
        ASSERT_NEAR(got.r, want.r, 1e-5f) << "pixel " << x << "," << y;
        ASSERT_NEAR(got.g, want.g, 1e-5f) << "pixel " << x << "," << y;
        ASSERT_NEAR(got.b, want.b, 1e-5f) << "pixel " << x << "," << y;
        ++checked;
      }
    EXPECT_GT(checked, kRes * kRes / 2);
  }
}

// A bump ramp h = c x + 2c y (texel column x, row y) tilts the shading normal against the unit tangent (+x, along
// dp/du) by c and against the unit bitangent (dp/dv's side: -y) by 2c, per unit of bumpmapMultiplier k (the rule of
// renderer/texture/, checked alone in BumpMap.RampAlongBothAxesTiltsAgainstTangentAndBitangent): every sample's N is
// normalize(-kc, 2kc, 1), turned to the camera, under every integrator.
TEST(Aov, NormalIsTheBumpMappedShadingNormal) {
  constexpr float c = 0.01f, k = 20.0f;
  const std::string image =
      write_test_exr("ramp.exr", 64, 64, [&](int x, int y) { return Rgb(c * float(x) + 2.0f * c * float(y)); });
  const std::string texture = R"(<Texture id="1" bumpmap="true" bumpmapMultiplier=")" + std::to_string(k) +
                              R"("><ImageName>)" + image + R"(</ImageName><Interpolation>bilinear</Interpolation>
    <DecalMode>replace_kd</DecalMode><Normalizer>1</Normalizer></Texture>)";
  const SceneDesc scene = textured_plane(texture, "kiln");
  const Vec3f want = normalize(Vec3f(-k * c, 2.0f * k * c, 1.0f));
  for (const auto& [name, settings] : every_integrator()) {
    SCOPED_TRACE(name);
    const Film film = render_film(scene, settings, 4);
    for (int y = 0; y < kRes; ++y)
      for (int x = 0; x < kRes; ++x) {
        const Vec3f n = film.surface_mean(x, y).n;
        ASSERT_NEAR(angle_between(n, want), 0.0f, 1e-3f)
            << "pixel " << x << "," << y << ": " << n.x << " " << n.y << " " << n.z;
      }
  }
}

// A replace_all texture gives the surface's colour outright: the colour a camera sample brings back is its texel, and
// so is its albedo (clamped to [0, 1]). With a black background every pixel's albedo is its colour exactly (same
// samples, same filter weights), whatever the texture shows: the CENG795 earth sphere, alone (its floor removed), its
// texture's DecalMode made replace_all, under every integrator.
TEST(Aov, ReplaceAllAlbedoIsTheColourTheImageShows) {
  const std::string path =
      std::string(KILN_SHARED_DIR) + "/scenes/ceng795/regression/hw4_2019/sphere_texture_replace_bilinear.xml";
  KILN_NEED_SHARED_PATH(path);
  SceneDesc scene = load_scene(path);
  scene.meshes.clear();  // the untextured floor
  ASSERT_EQ(scene.textures.size(), 1u);
  scene.textures[0].decal = DecalMode::ReplaceAll;
  scene.cameras[0].width = scene.cameras[0].height = 48;
  for (const auto& [name, settings] : every_integrator()) {
    SCOPED_TRACE(name);
    const Film film = render_film(scene, settings, 4);
    const Image colour = film.mean();
    double sum = 0;
    for (int y = 0; y < colour.height(); ++y)
      for (int x = 0; x < colour.width(); ++x) {
        const Rgb a = film.surface_mean(x, y).albedo, c = colour.at(x, y);
        ASSERT_EQ(a, c) << "pixel " << x << "," << y << ": albedo " << a.r << " " << a.g << " " << a.b << ", colour "
                        << c.r << " " << c.g << " " << c.b;
        sum += c.luminance();
      }
    EXPECT_GT(sum, 1.0) << "the sphere must be in view";
  }
}

// The AOVs look through mirrors: a camera that sees the textured plane only in a mirror records the plane's albedo
// and its depth along the path (the mirror image's distance), not the mirror's.
TEST(Aov, MirrorsAreLookedThrough) {
  const Rgb texel(0.1f, 0.2f, 0.05f);
  const std::string image = write_test_exr("flat.exr", 1, 1, [&](int, int) { return texel; });
  SceneDesc scene = textured_plane(R"(<Texture id="1"><ImageName>)" + image +
                                       R"(</ImageName><Interpolation>nearest</Interpolation><DecalMode>replace_kd</DecalMode>
    <Normalizer>1</Normalizer></Texture>)",
                                   "kiln");
  // Turn the camera around (+z) to face a mirror at z = 1: it sees the plane at z = -2 reflected, 1 + 3 = 4 away.
  CameraDesc& cam = scene.cameras[0];
  cam.gaze = Vec3f(0, 0, 1);
  MaterialDesc mirror;
  mirror.type = MaterialType::Mirror;
  mirror.mirror = Rgb(1.0f);
  scene.materials.push_back(mirror);
  MeshDesc m = scene.meshes[0];
  for (Vec3f& v : m.positions) v.z = 1.0f;
  m.material = int(scene.materials.size()) - 1;
  m.textures.clear();
  scene.meshes.push_back(m);
  const Film film = render_film(scene, IntegratorSettings{PathSettings{}}, 4);
  const int x = kRes / 2, y = kRes / 2;
  const VisibleSurface v = film.surface_mean(x, y);
  EXPECT_NEAR(v.albedo.g, texel.g * kPi, 1e-5f);
  EXPECT_NEAR(v.p.z, -2.0f, 1e-4f);
  EXPECT_NEAR(v.z, 4.0f, 0.02f);  // the pixel's rays lean by at most 1/16 from the axis: 4.008
}

}  // namespace
}  // namespace kiln::test
