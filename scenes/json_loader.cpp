#include "scenes/json_loader.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <map>
#include <string_view>

#include "core/error.h"
#include "scenes/obj_loader.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// Students hard-coded the IOR of their "translucent" extension; glass is the usual choice.
constexpr float kDefaultTranslucentIor = 1.5f;
// |sin| of the angle between view direction and ref_up below which the camera basis is undefined.
constexpr float kMinUpViewSine = 1e-4f;

std::string join(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}
std::string element(const std::string& parent, size_t i) { return parent + "[" + std::to_string(i) + "]"; }

// Reads typed values from the parsed document; every message names the config file and the key path.
class ConfigReader {
 public:
  ConfigReader(std::string file, SceneDesc& scene) : file_(std::move(file)), scene_(scene) {}

  [[noreturn]] void fail(const std::string& key_path, const std::string& message) const {
    throw Error(file_, key_path, message);
  }
  void warn(const std::string& key_path, const std::string& message) {
    scene_.warnings.push_back(Error::format(file_, key_path, message));
  }

  void check_keys(const json& obj, const std::string& path, std::initializer_list<std::string_view> known) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool found = false;
      for (std::string_view k : known) found = found || it.key() == k;
      if (!found) warn(join(path, it.key()), "unknown key, ignored");
    }
  }

  const json& require(const json& obj, const std::string& path, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(join(path, key), "missing required key");
    return *it;
  }

  const json& object(const json& value, const std::string& path) const {
    if (!value.is_object()) fail(path, std::string("expected an object, got ") + value.type_name());
    return value;
  }

  const json& array(const json& value, const std::string& path) const {
    if (!value.is_array()) fail(path, std::string("expected an array, got ") + value.type_name());
    return value;
  }

  float number(const json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, std::string("expected a number, got ") + value.type_name());
    const double d = value.get<double>();
    if (!std::isfinite(d) || std::abs(d) > std::numeric_limits<float>::max())
      fail(path, "number is not finite in single precision");
    return static_cast<float>(d);
  }

  // The skeleton converts numbers freely; an integral float (256.0) is accepted, 1.5 is not.
  int integer(const json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, std::string("expected an integer, got ") + value.type_name());
    const double d = value.get<double>();
    if (d != std::trunc(d)) fail(path, "expected an integer, got " + value.dump());
    if (d < std::numeric_limits<int>::min() || d > std::numeric_limits<int>::max())
      fail(path, "integer " + value.dump() + " is out of range");
    return static_cast<int>(d);
  }

  bool boolean(const json& value, const std::string& path) const {
    if (!value.is_boolean()) fail(path, std::string("expected true or false, got ") + value.type_name());
    return value.get<bool>();
  }

  std::string string(const json& value, const std::string& path) const {
    if (!value.is_string()) fail(path, std::string("expected a string, got ") + value.type_name());
    return value.get<std::string>();
  }

  // The skeleton reads C arrays: fewer elements are an error, extra ones are ignored (warned about here).
  const json& fixed_array(const json& value, const std::string& path, size_t n) {
    array(value, path);
    if (value.size() < n)
      fail(path, "expected " + std::to_string(n) + " elements, got " + std::to_string(value.size()));
    if (value.size() > n)
      warn(path, "has " + std::to_string(value.size()) + " elements; only the first " + std::to_string(n) +
                     " are used");
    return value;
  }

  Vec3f vec3(const json& value, const std::string& path) {
    fixed_array(value, path, 3);
    return {number(value[0], element(path, 0)), number(value[1], element(path, 1)),
            number(value[2], element(path, 2))};
  }

  Rgb rgb(const json& value, const std::string& path) {
    const Vec3f v = vec3(value, path);
    if (v.x < 0 || v.y < 0 || v.z < 0) fail(path, "colour components must not be negative");
    return {v.x, v.y, v.z};
  }

  float positive(const json& value, const std::string& path) const {
    const float x = number(value, path);
    if (!(x > 0.0f)) fail(path, "must be greater than 0, got " + value.dump());
    return x;
  }

 private:
  std::string file_;
  SceneDesc& scene_;
};

json parse_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path, "", "config file does not exist");
  if (!fs::is_regular_file(path, ec)) throw Error(path, "", "not a regular file");
  const std::string text = read_file_bytes(path);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range.406 for a number literal that overflows a double ("1E400").
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix; keep "parse error at line L, column C: ...".
    std::string what = e.what();
    if (auto pos = what.find("] "); what.rfind("[json.exception", 0) == 0 && pos != std::string::npos)
      what.erase(0, pos + 2);
    throw Error(path, "", "invalid JSON: " + what);
  }
}

void read_camera(ConfigReader& r, const json& root, SceneDesc& scene, const std::string& config_path) {
  const std::string cam_path = "cam_config";
  const json& cam = r.object(r.require(root, "", "cam_config"), cam_path);
  r.check_keys(cam, cam_path, {"position", "look_at", "ref_up", "vertical_fov", "focal_length"});
  CameraDesc c;
  c.id = cam_path;
  c.position = r.vec3(r.require(cam, cam_path, "position"), join(cam_path, "position"));
  const Vec3f look_at = r.vec3(r.require(cam, cam_path, "look_at"), join(cam_path, "look_at"));
  const Vec3f ref_up = r.vec3(r.require(cam, cam_path, "ref_up"), join(cam_path, "ref_up"));
  const float vfov = r.positive(r.require(cam, cam_path, "vertical_fov"), join(cam_path, "vertical_fov"));
  const float focal = r.positive(r.require(cam, cam_path, "focal_length"), join(cam_path, "focal_length"));
  if (vfov >= 180.0f) r.fail(join(cam_path, "vertical_fov"), "must be below 180 degrees");

  const Vec3f forward = look_at - c.position;
  if (!is_finite(forward)) r.fail(join(cam_path, "look_at"), "look_at - position overflows single precision");
  if (length_squared(forward) == 0.0f) r.fail(join(cam_path, "look_at"), "equals cam_config.position");
  if (length_squared(ref_up) == 0.0f ||
      length(cross(normalize(forward), normalize(ref_up))) < kMinUpViewSine)
    r.fail(join(cam_path, "ref_up"), "is zero or parallel to the view direction");
  c.gaze = normalize(forward);
  c.up = normalize(ref_up);
  c.use_fov = true;
  // focal_length scales the image-plane half extents while the plane stays at distance 1.
  c.fov_y_deg = degrees(2.0f * std::atan(focal * std::tan(radians(vfov) * 0.5f)));

  const std::string res_path = "image_resolution";
  const json& res = r.fixed_array(r.require(root, "", "image_resolution"), res_path, 2);
  c.width = r.integer(res[0], element(res_path, 0));
  c.height = r.integer(res[1], element(res_path, 1));
  if (c.width <= 0) r.fail(element(res_path, 0), "width must be greater than 0");
  if (c.height <= 0) r.fail(element(res_path, 1), "height must be greater than 0");

  c.num_samples = r.integer(r.require(root, "", "spp"), "spp");
  if (c.num_samples <= 0) r.fail("spp", "must be greater than 0");

  c.image_name = fs::path(config_path).stem().string() + ".exr";
  c.renderer = RendererKind::PathTracing;
  c.renderer_explicit = true;
  c.pt.next_event_estimation = true;  // the framework samples the area light at every vertex
  c.pt.importance_sampling = true;    // and continues with cosine-weighted hemisphere samples
  c.pt.russian_roulette = false;
  scene.cameras.push_back(c);
}

// Materials in file order (index i = materials[i]); returns name -> index.
std::map<std::string, int> read_materials(ConfigReader& r, const json& root, SceneDesc& scene, int lambert) {
  const std::string list_path = "materials";
  const json& list = r.array(r.require(root, "", "materials"), list_path);
  std::map<std::string, int> by_name;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = element(list_path, i);
    const json& m = r.object(list[i], path);
    const std::string name = r.string(r.require(m, path, "name"), join(path, "name"));
    const std::string type = r.string(r.require(m, path, "type"), join(path, "type"));
    if (name.empty()) r.fail(join(path, "name"), "must not be empty");
    if (by_name.count(name)) r.fail(join(path, "name"), "duplicate material name '" + name + "'");

    MaterialDesc desc;
    desc.id = static_cast<int>(i) + 1;
    if (type == "diffuse") {
      r.check_keys(m, path, {"name", "type", "color"});
      desc.type = MaterialType::Plain;
      desc.brdf = lambert;
      desc.diffuse = r.rgb(r.require(m, path, "color"), join(path, "color"));
    } else if (type == "specular") {
      r.check_keys(m, path, {"name", "type", "color"});
      desc.type = MaterialType::Mirror;
      desc.mirror = m.contains("color") ? r.rgb(m["color"], join(path, "color")) : Rgb(1.0f);
    } else if (type == "translucent") {
      r.check_keys(m, path, {"name", "type", "color", "ior"});
      desc.type = MaterialType::Dielectric;
      desc.refraction_index =
          m.contains("ior") ? r.positive(m["ior"], join(path, "ior")) : kDefaultTranslucentIor;
      desc.has_refraction_index = true;
      if (m.contains("color") && r.rgb(m["color"], join(path, "color")) != Rgb(1.0f))
        r.warn(join(path, "color"), "tint of a translucent material is ignored (Kiln's dielectric is clear)");
    } else {
      r.fail(join(path, "type"),
             "unknown material type '" + type + "' (expected \"diffuse\", \"specular\" or \"translucent\")");
    }
    by_name[name] = static_cast<int>(scene.materials.size());
    scene.materials.push_back(desc);
  }
  return by_name;
}

void read_objects(ConfigReader& r, const json& root, SceneDesc& scene, const std::map<std::string, int>& materials,
                  const fs::path& config_dir) {
  const std::string list_path = "objects";
  const json& list = r.array(r.require(root, "", "objects"), list_path);
  std::map<std::string, MeshDesc> cache;  // the same OBJ placed twice is parsed once
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = element(list_path, i);
    const json& o = r.object(list[i], path);
    r.check_keys(o, path, {"obj_file_path", "material_name", "translate", "scale", "has_bvh"});
    const std::string file_key = join(path, "obj_file_path");
    const std::string obj_file = r.string(r.require(o, path, "obj_file_path"), file_key);
    const std::string material_key = join(path, "material_name");
    const std::string material = r.string(r.require(o, path, "material_name"), material_key);
    const Vec3f translate = r.vec3(r.require(o, path, "translate"), join(path, "translate"));
    const float scale = r.positive(r.require(o, path, "scale"), join(path, "scale"));
    if (!std::isfinite(1.0f / scale))
      r.fail(join(path, "scale"), "is too small: its inverse overflows single precision");
    r.boolean(r.require(o, path, "has_bvh"), join(path, "has_bvh"));  // acceleration hint only

    auto mat = materials.find(material);
    if (mat == materials.end()) {
      std::string known;
      for (const auto& [name, index] : materials) known += (known.empty() ? "" : ", ") + name;
      r.fail(material_key, "no material named '" + material + "' (defined: " + (known.empty() ? "none" : known) +
                               ")");
    }
    if (obj_file.empty()) r.fail(file_key, "must not be empty");

    // The skeleton resolves against the working directory; relative to the config is the robust equivalent.
    fs::path resolved(obj_file);
    if (resolved.is_relative()) resolved = config_dir / resolved;
    const std::string key = resolved.lexically_normal().string();
    auto cached = cache.find(key);
    if (cached == cache.end()) {
      try {
        cached = cache.emplace(key, load_obj(key)).first;
      } catch (const Error& e) {
        r.fail(file_key, "cannot load '" + obj_file + "': " + e.what());
      }
    }
    MeshDesc mesh = cached->second;
    mesh.name = path + " (" + fs::path(obj_file).filename().string() + ")";
    mesh.material = mat->second;
    mesh.to_world = Transform::translate(translate) * Transform::scale(Vec3f(scale));
    scene.meshes.push_back(std::move(mesh));
  }
}

// The framework's SquareAreaLight: a horizontal rectangle facing -Y, emitting on that side only.
void read_light(ConfigReader& r, const json& root, SceneDesc& scene, int black_material) {
  const std::string light_path = "light_config";
  const json& l = r.object(r.require(root, "", "light_config"), light_path);
  r.check_keys(l, light_path, {"position", "size", "radiance"});
  const Vec3f centre = r.vec3(r.require(l, light_path, "position"), join(light_path, "position"));
  const std::string size_key = join(light_path, "size");
  const json& size = r.fixed_array(r.require(l, light_path, "size"), size_key, 2);
  const float hx = 0.5f * r.positive(size[0], element(size_key, 0));
  const float hz = 0.5f * r.positive(size[1], element(size_key, 1));
  const Rgb radiance = r.rgb(r.require(l, light_path, "radiance"), join(light_path, "radiance"));

  MeshDesc quad;
  quad.name = light_path;
  quad.positions = {centre + Vec3f(-hx, 0, -hz), centre + Vec3f(hx, 0, -hz), centre + Vec3f(hx, 0, hz),
                    centre + Vec3f(-hx, 0, hz)};
  for (const Vec3f& p : quad.positions)
    if (!is_finite(p)) r.fail(light_path, "a corner (position +- size / 2) overflows single precision");
  quad.indices = {0, 1, 2, 0, 2, 3};  // (v1-v0)x(v2-v0) = (0, -4 hx hz, 0): facing down
  quad.material = black_material;
  quad.emission = radiance;
  scene.meshes.push_back(std::move(quad));
}

}  // namespace

SceneDesc load_cs171_json(const std::string& path) {
  SceneDesc scene;
  scene.source_path = path;
  scene.format = "cs171-json";
  scene.rules = SceneRules::Cs171Course;
  scene.png_gamma_encode = true;  // the framework writes pow(L, 1/2.2) to its PNG
  ConfigReader r(path, scene);

  const json root = parse_file(path);
  r.object(root, "");
  r.check_keys(root, "",
               {"spp", "max_depth", "image_resolution", "cam_config", "light_config", "materials", "objects"});

  read_camera(r, root, scene, path);
  const int max_depth = r.integer(r.require(root, "", "max_depth"), "max_depth");
  if (max_depth < 1) r.fail("max_depth", "must be at least 1");
  scene.max_recursion_depth = max_depth;

  BrdfDesc lambert;
  lambert.id = 1;
  lambert.kind = BrdfKind::Lambert;
  scene.brdfs.push_back(lambert);
  const int lambert_index = 0;

  const auto materials = read_materials(r, root, scene, lambert_index);
  fs::path config_dir = fs::path(path).parent_path();
  if (config_dir.empty()) config_dir = ".";
  read_objects(r, root, scene, materials, config_dir);

  // The light only emits: a ray that hits it ends there, as with the framework's Interaction::LIGHT.
  MaterialDesc black;
  black.id = static_cast<int>(scene.materials.size()) + 1;
  black.brdf = lambert_index;
  const int black_index = static_cast<int>(scene.materials.size());
  scene.materials.push_back(black);
  read_light(r, root, scene, black_index);
  return scene;
}

}  // namespace kiln
