#include "scenes/pbrt/camera.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

// pbrt-v4's defaults.
constexpr int kDefaultXResolution = 1280, kDefaultYResolution = 720;
constexpr float kDefaultFov = 90.0f;
constexpr float kDefaultFocalDistance = 1e6f;
constexpr int kDefaultPixelSamples = 16;
constexpr float kGaussianRadius = 1.5f, kGaussianSigma = 0.5f, kBoxRadius = 0.5f, kWideFilterRadius = 2.0f;
// Largest image side accepted (the film is allocated from it).
constexpr int kMaxResolution = 1 << 16;
// Relative deviation from a rotation times a uniform scale beyond which the camera transform is reported.
constexpr float kRigidTolerance = 1e-3f;
constexpr float kDefaultIso = 100.0f;             // pbrt's imaging ratio is exposure * iso / 100
constexpr float kDefaultFilmDiagonalMm = 35.0f;
constexpr float kDefaultApertureDiameterMm = 1.0f;
constexpr float kDefaultFocusDistance = 10.0f;    // metres (realistic camera)
constexpr float kMillimetre = 0.001f;
constexpr size_t kLensColumns = 4;               // radius, thickness, eta, aperture diameter

struct PixelWindow {
  int x0, x1, y0, y1;
};

PixelWindow pixel_window(const PbrtParams& film, int xres, int yres, PbrtDiagnostics& diag) {
  PixelWindow w{0, xres, 0, yres};
  const std::vector<float> crop = film.get_floats("cropwindow");
  const std::vector<int64_t> bounds = film.get_ints("pixelbounds");
  if (!crop.empty()) {
    if (crop.size() != 4) film.fail(film.line(), "\"cropwindow\" takes 4 values (x0 x1 y0 y1)");
    for (float v : crop)
      if (v < 0.0f || v > 1.0f) film.fail(film.line(), "\"cropwindow\" values are fractions in [0, 1]");
    // pbrt's rounding: pixels ceil(res * start) up to, not including, ceil(res * end).
    w = {int(std::ceil(float(xres) * crop[0])), int(std::ceil(float(xres) * crop[1])),
         int(std::ceil(float(yres) * crop[2])), int(std::ceil(float(yres) * crop[3]))};
  }
  if (!bounds.empty()) {
    if (bounds.size() != 4) film.fail(film.line(), "\"pixelbounds\" takes 4 values (x0 x1 y0 y1)");
    if (!crop.empty()) diag.warn(film, "both \"cropwindow\" and \"pixelbounds\" given; \"pixelbounds\" is used");
    auto clampi = [](int64_t v, int hi) { return int(std::clamp<int64_t>(v, 0, hi)); };
    w = {clampi(bounds[0], xres), clampi(bounds[1], xres), clampi(bounds[2], yres), clampi(bounds[3], yres)};
  }
  if (w.x0 >= w.x1 || w.y0 >= w.y1)
    film.fail(film.line(), "the crop window holds no pixel (x " + std::to_string(w.x0) + ".." + std::to_string(w.x1) +
                               ", y " + std::to_string(w.y0) + ".." + std::to_string(w.y1) + ")");
  return w;
}

void apply_filter(const PbrtCameraInput& in, CameraDesc& c, PbrtDiagnostics& diag) {
  PixelFilterDesc f;
  const PbrtParams& ps = in.filter;
  const std::string& type = in.has_filter ? in.filter_type : std::string("gaussian");
  float default_radius = kWideFilterRadius;
  if (type == "box") {
    f.kind = PixelFilterKind::Box;
    default_radius = kBoxRadius;
  } else if (type == "gaussian") {
    f.kind = PixelFilterKind::Gaussian;
    default_radius = kGaussianRadius;
    f.sigma = ps.get_float("sigma", kGaussianSigma);
    if (!(f.sigma > 0.0f)) ps.fail(ps.line(), "\"sigma\" must be positive");
  } else if (type == "triangle") {
    f.kind = PixelFilterKind::Triangle;
  } else if (type == "mitchell") {
    f.kind = PixelFilterKind::Mitchell;
    f.b = ps.get_float("B", 1.0f / 3.0f);
    f.c = ps.get_float("C", 1.0f / 3.0f);
  } else {
    diag.warn(ps, "pixel filter \"" + type + "\" is not supported; pbrt's default gaussian is used");
    diag.unsupported("pbrt pixel filter \"" + type + "\"");
    for (const PbrtParam& p : ps.params()) p.used = true;
    f.kind = PixelFilterKind::Gaussian;
    f.sigma = kGaussianSigma;
    c.filter = f;
    c.filter->radius = kGaussianRadius;
    return;
  }
  const float xr = ps.get_float("xradius", default_radius), yr = ps.get_float("yradius", default_radius);
  if (!(xr > 0.0f) || !(yr > 0.0f)) ps.fail(ps.line(), "filter radii must be positive");
  if (xr != yr) {
    diag.warn(ps, "different x and y radii are not supported; both are " + std::to_string(xr));
    diag.unsupported("pbrt pixel filters with different x and y radii");
  }
  f.radius = xr;
  c.filter = f;
}


// Film: resolution, file name, crop, and pbrt's imaging ratio's iso; `gbuffer` and `spectral` read as `rgb`.
PixelWindow read_film(const PbrtCameraInput& in, CameraDesc& c, PbrtDiagnostics& diag, int& xres, int& yres) {
  const PbrtParams& film = in.film;
  if (in.film_type == "gbuffer") {
    c.aov_layers = true;
    diag.warn(film, "film \"gbuffer\": the image is written with Kiln's AOV layers (albedo, normal, depth, position, "
                    "variance)");
    if (film.has("coordinatesystem")) film.get_string("coordinatesystem", "camera");
  } else if (in.film_type == "spectral") {
    diag.warn(film, "film \"spectral\" is rendered as \"rgb\" (Kiln renders RGB, not spectral bins)");
    diag.unsupported("pbrt spectral film (rendered as RGB)");
    for (const char* p : {"nbuckets", "lambdamin", "lambdamax"})
      if (film.has(p)) film.get_float(p, 0.0f);
  } else if (in.film_type != "rgb") {
    film.fail(film.line(), "unknown film \"" + in.film_type + "\" (rgb, gbuffer, spectral)");
  }
  xres = film.get_int("xresolution", kDefaultXResolution);
  yres = film.get_int("yresolution", kDefaultYResolution);
  if (xres < 1 || yres < 1 || xres > kMaxResolution || yres > kMaxResolution)
    film.fail(film.line(), "resolution " + std::to_string(xres) + " x " + std::to_string(yres) + " is outside 1.." +
                               std::to_string(kMaxResolution));
  const std::string filename = film.get_string("filename", "pbrt.exr");
  std::string stem = std::filesystem::path(filename).stem().string();
  if (stem.empty()) stem = "pbrt";
  // Kiln writes linear EXR plus a PNG preview whatever extension the file asks for.
  c.image_name = stem + ".exr";
  const float iso = film.get_float("iso", kDefaultIso);
  if (!(iso > 0.0f)) film.fail(film.line(), "\"iso\" must be positive");
  c.film_scale = iso / kDefaultIso;
  if (const auto sensor = film.find_string("sensor"); sensor && *sensor != "cie1931") {
    diag.warn(film, "sensor " + in_quotes(*sensor) + " is not modelled; the CIE 1931 observer (sRGB) is used");
    diag.unsupported("pbrt camera sensors other than cie1931");
  }
  if (const float wb = film.get_float("whitebalance", 0.0f); wb != 0.0f) {
    diag.warn(film, "\"whitebalance\" is not applied (Kiln keeps the scene's RGB)");
    diag.unsupported("pbrt film white balance");
  }
  c.max_component = film.get_float("maxcomponentvalue", kInfinity);
  if (!(c.max_component > 0.0f)) film.fail(film.line(), "\"maxcomponentvalue\" must be positive");
  if (film.has("savefp16")) film.get_bool("savefp16", true);
  return pixel_window(film, xres, yres, diag);
}

// The shutter interval; the exposure time (close - open) joins the imaging ratio as in pbrt.
PbrtShutter read_shutter(const PbrtParams& cam, CameraDesc& c, PbrtDiagnostics& diag) {
  PbrtShutter s{cam.get_float("shutteropen", 0.0f), cam.get_float("shutterclose", 1.0f)};
  if (s.close < s.open) {
    diag.warn(cam, "\"shutterclose\" is before \"shutteropen\"; they are swapped (as pbrt does)");
    std::swap(s.open, s.close);
  }
  if (!(s.close > s.open))
    cam.fail(cam.line(), "\"shutteropen\" and \"shutterclose\" are equal: the shutter never opens");
  c.film_scale *= s.close - s.open;
  return s;
}

struct CameraFrame {
  Vec3f position, gaze, up;
  bool left_handed = false;
  float scale = 1.0f;  // the uniform scale of world-from-camera (camera-space lengths grow by it)
};

CameraFrame camera_frame(const Transform& camera_from_world, const PbrtParams& cam, PbrtDiagnostics& diag) {
  if (!camera_from_world.invertible())
    cam.fail(cam.line(), "the camera transform is singular: the camera's position and axes cannot be found");
  const Transform world_from_camera = camera_from_world.inverse();
  const Vec3f right = world_from_camera.vector({1, 0, 0}), up = world_from_camera.vector({0, 1, 0}),
              fwd = world_from_camera.vector({0, 0, 1});
  const float sr = length(right), su = length(up), sf = length(fwd);
  if (!(sr > 0.0f && su > 0.0f && sf > 0.0f) || !is_finite(right) || !is_finite(up) || !is_finite(fwd))
    cam.fail(cam.line(), "the camera transform is degenerate");
  CameraFrame f;
  f.position = world_from_camera.point({0, 0, 0});
  if (!is_finite(f.position)) cam.fail(cam.line(), "the camera position is not finite");
  f.gaze = fwd / sf;
  f.up = up / su;
  f.left_handed = dot(right, cross(up, fwd)) > 0.0f;
  f.scale = sf;
  const bool rigid = std::abs(dot(right / sr, f.up)) < kRigidTolerance &&
                     std::abs(dot(right / sr, f.gaze)) < kRigidTolerance &&
                     std::abs(dot(f.up, f.gaze)) < kRigidTolerance && std::abs(sr - sf) <= kRigidTolerance * sf &&
                     std::abs(su - sf) <= kRigidTolerance * sf;
  if (!rigid) {
    diag.warn(cam, "the camera transform shears or scales unevenly; Kiln keeps only its position and orientation");
    diag.unsupported("shearing or unevenly scaling camera transforms");
  }
  return f;
}

// pbrt's screen window: the frame aspect ratio's default window unless "screenwindow" gives one.
std::array<float, 4> screen_window(const PbrtParams& cam, int xres, int yres) {
  const float aspect = cam.get_float("frameaspectratio", float(xres) / float(yres));
  if (!(aspect > 0.0f)) cam.fail(cam.line(), "\"frameaspectratio\" must be positive");
  std::vector<float> screen = cam.get_floats("screenwindow");
  if (screen.empty())
    screen = aspect > 1.0f ? std::vector<float>{-aspect, aspect, -1.0f, 1.0f}
                           : std::vector<float>{-1.0f, 1.0f, -1.0f / aspect, 1.0f / aspect};
  if (screen.size() != 4 || !(screen[0] < screen[1]) || !(screen[2] < screen[3]))
    cam.fail(cam.line(), "\"screenwindow\" takes 4 values x0 < x1, y0 < y1");
  return {screen[0], screen[1], screen[2], screen[3]};
}

// The part of the screen window the crop keeps, as CameraDesc::near_plane (raster x runs with camera +x from the
// left edge; raster y runs down from the top).
void crop_screen(CameraDesc& c, std::array<float, 4> s, const PixelWindow& win, int xres, int yres) {
  const float l = s[0], r = s[1], b = s[2], top = s[3];
  c.near_plane = {l + (r - l) * float(win.x0) / float(xres), l + (r - l) * float(win.x1) / float(xres),
                  top - (top - b) * float(win.y1) / float(yres), top - (top - b) * float(win.y0) / float(yres)};
}

void thin_lens(const PbrtParams& cam, CameraDesc& c, float scale) {
  const float lens_radius = cam.get_float("lensradius", 0.0f);
  const float focal = cam.get_float("focaldistance", kDefaultFocalDistance);
  if (lens_radius < 0.0f) cam.fail(cam.line(), "\"lensradius\" must not be negative");
  if (lens_radius > 0.0f) {
    if (!(focal > 0.0f)) cam.fail(cam.line(), "\"focaldistance\" must be positive");
    // Camera-space lengths scale with a uniform scale in the camera transform.
    c.aperture_size = 2.0f * lens_radius * scale;
    c.focus_distance = focal * scale;
    c.disk_lens = true;
  }
}

void perspective(const PbrtParams& cam, CameraDesc& c, const PixelWindow& win, int xres, int yres, float scale) {
  const float fov = cam.get_float("fov", kDefaultFov);
  if (!(fov > 0.0f && fov < 180.0f)) cam.fail(cam.line(), "\"fov\" must be between 0 and 180 degrees");
  // fov spans the screen window's shorter side [-1, 1] at camera-space depth 1.
  const float t = std::tan(radians(fov) * 0.5f);
  std::array<float, 4> s = screen_window(cam, xres, yres);
  for (float& v : s) v *= t;
  crop_screen(c, s, win, xres, yres);
  c.fov_y_deg = degrees(2.0f * std::atan(s[3]));
  thin_lens(cam, c, scale);
}

void orthographic(const PbrtParams& cam, CameraDesc& c, const PixelWindow& win, int xres, int yres, float scale) {
  c.projection = CameraProjection::Orthographic;
  std::array<float, 4> s = screen_window(cam, xres, yres);
  for (float& v : s) v *= scale;  // camera-space units: a uniformly scaled camera sees a larger window
  crop_screen(c, s, win, xres, yres);
  thin_lens(cam, c, scale);
}

void spherical(const PbrtParams& cam, CameraDesc& c, int xres, int yres) {
  c.projection = CameraProjection::Spherical;
  const std::string mapping = cam.get_string("mapping", "equalarea");
  if (mapping == "equalarea")
    c.spherical_mapping = SphericalMapping::EqualArea;
  else if (mapping == "equirectangular")
    c.spherical_mapping = SphericalMapping::Equirectangular;
  else
    cam.fail(cam.line(), "unknown \"mapping\" " + in_quotes(mapping) + " (equalarea, equirectangular)");
  // pbrt reads these for every camera; a spherical camera has no use for them.
  screen_window(cam, xres, yres);
  cam.get_float("lensradius", 0.0f);
  cam.get_float("focaldistance", kDefaultFocalDistance);
}

void realistic(const PbrtCameraInput& in, CameraDesc& c, PbrtDiagnostics& diag) {
  const PbrtParams& cam = in.camera;
  c.projection = CameraProjection::Realistic;
  const auto name = cam.find_string("lensfile");
  if (!name || name->empty()) cam.fail(cam.line(), "a realistic camera needs \"string lensfile\"");
  const std::string path = in.resolve(*name, cam.line());
  std::string text;
  try {
    text = read_file_bytes(path);
  } catch (const Error& e) {
    cam.fail(cam.line(), std::string("cannot read the lens file: ") + e.what());
  }
  LensSystemDesc lens;
  lens.file = path;
  lens.directive = cam.file() + ": " + cam.location(cam.line());
  try {
    lens.interfaces = parse_lens_file(text, path);
  } catch (const Error& e) {
    cam.fail(cam.line(), std::string("lens file ") + e.what());
  }
  float aperture = cam.get_float("aperturediameter", kDefaultApertureDiameterMm) * kMillimetre;
  if (!(aperture > 0.0f)) cam.fail(cam.line(), "\"aperturediameter\" must be positive");
  size_t stops = 0;
  for (LensInterfaceDesc& e : lens.interfaces) {
    if (e.curvature_radius != 0.0f) continue;
    ++stops;
    if (aperture > 2.0f * e.aperture_radius)
      diag.warn(cam, "\"aperturediameter\" " + std::to_string(aperture / kMillimetre) +
                         " mm is larger than the lens's stop (" + std::to_string(2.0f * e.aperture_radius / kMillimetre) +
                         " mm); the stop's is used");
    else
      e.aperture_radius = 0.5f * aperture;
  }
  if (stops == 0) diag.warn(cam, "the lens file has no aperture stop (radius 0); \"aperturediameter\" has no effect");
  lens.focus_distance = cam.get_float("focusdistance", kDefaultFocusDistance);
  if (!(lens.focus_distance > 0.0f)) cam.fail(cam.line(), "\"focusdistance\" must be positive");
  lens.film_diagonal = in.film.get_float("diagonal", kDefaultFilmDiagonalMm) * kMillimetre;
  if (!(lens.film_diagonal > 0.0f)) in.film.fail(in.film.line(), "\"diagonal\" must be positive");
  if (const auto shape = cam.find_string("aperture"); shape && !shape->empty()) {
    diag.warn(cam, "aperture shape " + in_quotes(*shape) + " is not supported; the stop stays circular");
    diag.unsupported("shaped apertures (pbrt realistic camera \"aperture\")");
  }
  c.lens = std::move(lens);
}

// A moving camera: the pose at the end time, as the frame of the start pose is read.
void camera_motion(const PbrtCameraInput& in, const PbrtShutter& shutter, CameraDesc& c, PbrtDiagnostics& diag) {
  if (!in.camera_from_world_end) return;
  const CameraFrame end = camera_frame(*in.camera_from_world_end, in.camera, diag);
  if (end.left_handed != c.left_handed)
    in.camera.fail(in.camera.line(), "the camera transform mirrors at one end of its motion and not at the other");
  CameraMotionDesc m;
  m.position = end.position;
  m.gaze = end.gaze;
  m.up = end.up;
  m.start_time = shutter.to_kiln(in.transform_start_time);
  m.end_time = shutter.to_kiln(in.transform_end_time);
  c.motion = m;
}

}  // namespace

std::vector<LensInterfaceDesc> parse_lens_file(const std::string& text, const std::string& path) {
  std::vector<LensInterfaceDesc> out;
  std::string_view rest(text);
  for (int line = 1; !rest.empty(); ++line) {
    const size_t eol = std::min(rest.find('\n'), rest.size());
    std::string_view l = rest.substr(0, eol);
    rest.remove_prefix(std::min(eol + 1, rest.size()));
    l = l.substr(0, std::min(l.find('#'), l.size()));
    const std::vector<std::string_view> tokens = split_whitespace(l);
    if (tokens.empty()) continue;
    const std::string where = "line " + std::to_string(line);
    if (tokens.size() != kLensColumns)
      throw Error(path, where,
                  "has " + std::to_string(tokens.size()) +
                      " values; a lens interface takes 4 (curvature radius, thickness, index of refraction, aperture "
                      "diameter; lengths in mm)");
    float v[kLensColumns];
    for (size_t i = 0; i < kLensColumns; ++i) {
      const auto x = to_float(tokens[i]);
      if (!x) throw Error(path, where, "'" + std::string(tokens[i].substr(0, 40)) + "' is not a number");
      v[i] = *x;
    }
    if (v[1] < 0.0f) throw Error(path, where, "the thickness must not be negative");
    if (v[2] < 0.0f) throw Error(path, where, "the index of refraction must not be negative (0 means air)");
    if (!(v[3] > 0.0f)) throw Error(path, where, "the aperture diameter must be positive");
    out.push_back({v[0] * kMillimetre, v[1] * kMillimetre, v[2], 0.5f * v[3] * kMillimetre});
  }
  if (out.empty()) throw Error(path, "", "the lens file lists no interfaces");
  return out;
}

PbrtCamera make_pbrt_camera(const PbrtCameraInput& in, PbrtDiagnostics& diag) {
  PbrtCamera out;
  CameraDesc& c = out.desc;
  c.id = "camera";
  c.renderer = RendererKind::PathTracing;
  c.renderer_explicit = true;

  int xres = 0, yres = 0;
  const PixelWindow win = read_film(in, c, diag, xres, yres);
  c.width = win.x1 - win.x0;
  c.height = win.y1 - win.y0;
  c.full_width = xres;
  c.full_height = yres;
  c.crop_x = win.x0;
  c.crop_y = win.y0;
  c.use_fov = false;
  c.near_distance = 1.0f;

  const PbrtParams& cam = in.camera;
  const CameraFrame frame = camera_frame(in.camera_from_world, cam, diag);
  c.position = frame.position;
  c.gaze = frame.gaze;
  c.up = frame.up;
  c.left_handed = frame.left_handed;
  out.shutter = read_shutter(cam, c, diag);
  if (in.camera_type == "perspective")
    perspective(cam, c, win, xres, yres, frame.scale);
  else if (in.camera_type == "orthographic")
    orthographic(cam, c, win, xres, yres, frame.scale);
  else if (in.camera_type == "spherical")
    spherical(cam, c, xres, yres);
  else if (in.camera_type == "realistic")
    realistic(in, c, diag);
  else
    cam.fail(cam.line(), "unknown camera \"" + in.camera_type + "\" (perspective, orthographic, spherical, realistic)");
  if (in.camera_type != "realistic" && in.film.has("diagonal")) in.film.get_float("diagonal", kDefaultFilmDiagonalMm);
  camera_motion(in, out.shutter, c, diag);

  c.num_samples = in.sampler.get_int("pixelsamples", kDefaultPixelSamples);
  if (c.num_samples < 1) in.sampler.fail(in.sampler.line(), "\"pixelsamples\" must be at least 1");
  if (in.has_sampler)
    diag.warn(in.sampler, "sampler \"" + in.sampler_type +
                              "\" is replaced by Kiln's stratified sampler (same expected image, its own noise)");
  apply_filter(in, c, diag);
  return out;
}

}  // namespace kiln
