#include "scenes/mesh_scene.h"

#include <filesystem>

#include "core/bounds.h"
#include "core/error.h"

namespace kiln {
namespace {

// The quick-look camera looks at the mesh from the front-right and above, framing its bounding sphere.
constexpr float kQuickLookFovDeg = 35.0f;
constexpr int kQuickLookResolution = 512;

}  // namespace

SceneDesc make_mesh_scene(MeshDesc mesh, const std::string& path) {
  SceneDesc s;
  s.source_path = path;
  s.format = std::filesystem::path(path).extension() == ".obj" ? "obj" : "ply";
  Bounds3f b;
  for (const Vec3f& p : mesh.positions) b.extend(p);
  if (b.empty()) throw Error(path, "", "mesh has no vertices");
  const Vec3f c = b.center();
  const float r = std::max(0.5f * b.extent(), 1e-6f);

  MaterialDesc body;
  body.diffuse = Rgb(0.6f, 0.55f, 0.5f);
  body.specular = Rgb(0.2f);
  body.phong_exponent = 40.0f;
  BrdfDesc brdf;
  brdf.kind = BrdfKind::ModifiedBlinnPhong;
  brdf.exponent = 40.0f;
  brdf.normalized = true;
  s.brdfs.push_back(brdf);
  body.brdf = 0;
  MaterialDesc ground;
  ground.diffuse = Rgb(0.5f);
  ground.brdf = 1;
  BrdfDesc lambert;
  lambert.kind = BrdfKind::Lambert;
  s.brdfs.push_back(lambert);
  s.materials = {body, ground};

  mesh.material = 0;
  mesh.name = std::filesystem::path(path).filename().string();
  s.meshes.push_back(std::move(mesh));

  // Ground plane under the mesh, large enough to catch its shadow.
  MeshDesc plane;
  plane.name = "ground";
  const float y = b.lo.y, e = 20.0f * r;
  plane.positions = {{c.x - e, y, c.z - e}, {c.x + e, y, c.z - e}, {c.x + e, y, c.z + e}, {c.x - e, y, c.z + e}};
  plane.indices = {0, 2, 1, 0, 3, 2};
  plane.material = 1;
  s.meshes.push_back(std::move(plane));

  CameraDesc cam;
  cam.id = "auto";
  const Vec3f dir = normalize(Vec3f(0.6f, 0.45f, 1.0f));
  const float dist = r / std::sin(radians(kQuickLookFovDeg) * 0.5f) * 1.1f;
  cam.position = c + dir * dist;
  cam.gaze = -dir;
  cam.up = Vec3f(0, 1, 0);
  cam.use_fov = true;
  cam.fov_y_deg = kQuickLookFovDeg;
  cam.near_distance = 1.0f;
  cam.width = cam.height = kQuickLookResolution;
  cam.num_samples = 16;
  cam.image_name = std::filesystem::path(path).stem().string() + ".exr";
  cam.renderer = RendererKind::PathTracing;
  s.cameras.push_back(cam);

  // A square area light above and in front of the mesh, plus a dim sky-like ambient for the shadow side.
  AreaLightDesc light;
  light.position = c + Vec3f(0.5f * r, 3.0f * r, 1.5f * r);
  light.normal = normalize(c - light.position);
  light.size = 1.5f * r;
  light.radiance = Rgb(8.0f);
  s.area_lights.push_back(light);
  return s;
}

}  // namespace kiln
