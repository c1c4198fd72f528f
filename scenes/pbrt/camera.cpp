#include "scenes/pbrt/camera.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"

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
  if (xr != yr) diag.warn(ps, "different x and y radii are not supported; both are " + std::to_string(xr));
  f.radius = xr;
  c.filter = f;
}

}  // namespace

CameraDesc make_pbrt_camera(const PbrtCameraInput& in, PbrtDiagnostics& diag) {
  CameraDesc c;
  c.id = "camera";
  c.renderer = RendererKind::PathTracing;
  c.renderer_explicit = true;

  const PbrtParams& film = in.film;
  if (in.film_type != "rgb") {
    if (in.film_type != "gbuffer" && in.film_type != "spectral")
      film.fail(film.line(), "unknown film \"" + in.film_type + "\" (rgb, gbuffer, spectral)");
    diag.warn(film, "film \"" + in.film_type + "\" is rendered as \"rgb\"");
  }
  const int xres = film.get_int("xresolution", kDefaultXResolution);
  const int yres = film.get_int("yresolution", kDefaultYResolution);
  if (xres < 1 || yres < 1 || xres > kMaxResolution || yres > kMaxResolution)
    film.fail(film.line(), "resolution " + std::to_string(xres) + " x " + std::to_string(yres) + " is outside 1.." +
                               std::to_string(kMaxResolution));
  const std::string filename = film.get_string("filename", "pbrt.exr");
  std::string stem = std::filesystem::path(filename).stem().string();
  if (stem.empty()) stem = "pbrt";
  // Kiln writes linear EXR plus a PNG preview whatever extension the file asks for.
  c.image_name = stem + ".exr";
  const PixelWindow win = pixel_window(film, xres, yres, diag);

  const PbrtParams& cam = in.camera;
  if (in.camera_type != "perspective")
    cam.fail(cam.line(), "camera \"" + in.camera_type + "\" is not supported (Kiln renders \"perspective\" cameras)");
  const float fov = cam.get_float("fov", kDefaultFov);
  if (!(fov > 0.0f && fov < 180.0f)) cam.fail(cam.line(), "\"fov\" must be between 0 and 180 degrees");
  const float aspect = cam.get_float("frameaspectratio", float(xres) / float(yres));
  if (!(aspect > 0.0f)) cam.fail(cam.line(), "\"frameaspectratio\" must be positive");
  std::vector<float> screen = cam.get_floats("screenwindow");
  if (screen.empty())
    screen = aspect > 1.0f ? std::vector<float>{-aspect, aspect, -1.0f, 1.0f}
                           : std::vector<float>{-1.0f, 1.0f, -1.0f / aspect, 1.0f / aspect};
  if (screen.size() != 4 || !(screen[0] < screen[1]) || !(screen[2] < screen[3]))
    cam.fail(cam.line(), "\"screenwindow\" takes 4 values x0 < x1, y0 < y1");
  // fov spans the screen window's shorter side [-1, 1] at camera-space depth 1.
  const float t = std::tan(radians(fov) * 0.5f);
  const float l = screen[0] * t, r = screen[1] * t, b = screen[2] * t, top = screen[3] * t;
  c.use_fov = false;
  c.near_distance = 1.0f;
  // Raster x runs with camera +x from l; raster y runs down from the top.
  c.near_plane = {l + (r - l) * float(win.x0) / float(xres), l + (r - l) * float(win.x1) / float(xres),
                  top - (top - b) * float(win.y1) / float(yres), top - (top - b) * float(win.y0) / float(yres)};
  c.fov_y_deg = degrees(2.0f * std::atan(top));
  c.width = win.x1 - win.x0;
  c.height = win.y1 - win.y0;

  const Transform world_from_camera = in.camera_from_world.inverse();
  const Vec3f right = world_from_camera.vector({1, 0, 0}), up = world_from_camera.vector({0, 1, 0}),
              fwd = world_from_camera.vector({0, 0, 1});
  const float sr = length(right), su = length(up), sf = length(fwd);
  if (!(sr > 0.0f && su > 0.0f && sf > 0.0f) || !is_finite(right) || !is_finite(up) || !is_finite(fwd))
    cam.fail(cam.line(), "the camera transform is degenerate");
  c.position = world_from_camera.point({0, 0, 0});
  if (!is_finite(c.position)) cam.fail(cam.line(), "the camera position is not finite");
  c.gaze = fwd / sf;
  c.up = up / su;
  c.left_handed = dot(right, cross(up, fwd)) > 0.0f;
  const bool rigid = std::abs(dot(right / sr, c.up)) < kRigidTolerance &&
                     std::abs(dot(right / sr, c.gaze)) < kRigidTolerance &&
                     std::abs(dot(c.up, c.gaze)) < kRigidTolerance && std::abs(sr - sf) <= kRigidTolerance * sf &&
                     std::abs(su - sf) <= kRigidTolerance * sf;
  if (!rigid)
    diag.warn(cam, "the camera transform shears or scales unevenly; Kiln keeps only its position and orientation");

  const float lens_radius = cam.get_float("lensradius", 0.0f);
  const float focal = cam.get_float("focaldistance", kDefaultFocalDistance);
  if (lens_radius < 0.0f) cam.fail(cam.line(), "\"lensradius\" must not be negative");
  if (lens_radius > 0.0f) {
    if (!(focal > 0.0f)) cam.fail(cam.line(), "\"focaldistance\" must be positive");
    // Camera-space lengths scale with a uniform scale in the camera transform.
    c.aperture_size = 2.0f * lens_radius * sf;
    c.focus_distance = focal * sf;
    c.disk_lens = true;
  }

  c.num_samples = in.sampler.get_int("pixelsamples", kDefaultPixelSamples);
  if (c.num_samples < 1) in.sampler.fail(in.sampler.line(), "\"pixelsamples\" must be at least 1");
  if (in.has_sampler)
    diag.warn(in.sampler, "sampler \"" + in.sampler_type +
                              "\" is replaced by Kiln's stratified sampler (same expected image, its own noise)");
  apply_filter(in, c, diag);
  return c;
}

}  // namespace kiln
