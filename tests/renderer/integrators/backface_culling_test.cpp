// BackfaceCulling under the course's rules: with <BackfaceCulling>true</BackfaceCulling> camera rays pass through
// triangles whose (v1-v0)x(v2-v0) normal faces away from them; by default, with false, and under Kiln's rules they
// see them (README, "Course conventions").
#include <gtest/gtest.h>

#include "renderer/render_util.h"

namespace kiln::test {
namespace {

// Camera at the origin looking down -z at two quads: a near one of red ambient colour whose winding faces away from
// the camera, and a far one emitting green towards it.
SceneDesc two_quads(std::optional<bool> culling, SceneRules rules) {
  SceneDesc s;
  s.source_path = "culling.test";
  s.rules = rules;
  s.backface_culling = culling;
  s.ambient_light = Rgb(1.0f);
  MaterialDesc red, black;
  red.ambient = Rgb(1, 0, 0);
  s.materials = {red, black};
  auto quad = [](float z, bool facing_camera, int material) {
    MeshDesc m;
    m.name = "quad";
    m.positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
    m.indices = facing_camera ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
    m.material = material;
    return m;
  };
  s.meshes = {quad(-2, false, 0), quad(-4, true, 1)};
  s.meshes[1].emission = Rgb(0, 1, 0);
  CameraDesc cam;
  cam.id = "1";
  cam.gaze = {0, 0, -1};
  cam.use_fov = true;
  cam.fov_y_deg = 10;
  cam.width = cam.height = 4;
  s.cameras.push_back(cam);
  return s;
}

Rgb centre_pixel(const SceneDesc& s, RendererKind renderer) {
  SceneDesc scene = s;
  scene.cameras[0].renderer = renderer;
  const auto w = build_world(scene, {});
  const IntegratorSettings settings = scene_settings(scene.cameras[0], scene, w->features);
  return render_image(*w, scene.cameras[0], settings, 1).at(2, 2);
}

TEST(BackfaceCulling, CourseCameraRaysCullWhenTheSceneAsks) {
  for (RendererKind r : {RendererKind::RayTracing, RendererKind::PathTracing})
    EXPECT_EQ(centre_pixel(two_quads(true, SceneRules::Ceng795Course), r), Rgb(0, 1, 0));
}

TEST(BackfaceCulling, OffByDefaultOrInTheSceneOrUnderKilnsRulesSeesBackFaces) {
  for (std::optional<bool> culling : {std::optional<bool>(), std::optional<bool>(false)}) {
    EXPECT_EQ(centre_pixel(two_quads(culling, SceneRules::Ceng795Course), RendererKind::RayTracing), Rgb(1, 0, 0));
    // The course path tracer adds no ambient term: the near quad shows black instead of the emitter.
    EXPECT_EQ(centre_pixel(two_quads(culling, SceneRules::Ceng795Course), RendererKind::PathTracing), Rgb(0.0f));
  }
  SceneDesc kiln = two_quads(true, SceneRules::Kiln);
  const auto w = build_world(kiln, {});
  const IntegratorSettings settings = scene_settings(kiln.cameras[0], kiln, w->features);
  EXPECT_EQ(render_image(*w, kiln.cameras[0], settings, 1).at(2, 2), Rgb(0.0f))
      << "Kiln's path tracer does not cull: the near quad (no ambient term in Kiln's rules) hides the emitter";
}

TEST(BackfaceCulling, TheSettingIsTheRuleSetsAndShowsInTheDescription) {
  const SceneDesc on = two_quads(true, SceneRules::Ceng795Course);
  const IntegratorSettings s = scene_settings(on.cameras[0], on, kFeatureAll);
  EXPECT_TRUE(std::get<CourseRaySettings>(s.method).cull_camera_backfaces);
  EXPECT_NE(s.describe().find("backface culling"), std::string::npos) << s.describe();
  for (std::optional<bool> culling : {std::optional<bool>(), std::optional<bool>(false)}) {
    const SceneDesc off = two_quads(culling, SceneRules::Ceng795Course);
    EXPECT_FALSE(
        std::get<CourseRaySettings>(scene_settings(off.cameras[0], off, kFeatureAll).method).cull_camera_backfaces);
  }
}

}  // namespace
}  // namespace kiln::test
