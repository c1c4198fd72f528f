// pbrt-v4's camera, film, sampler and pixel filter as one Kiln CameraDesc.
//   Camera "perspective"  "fov" (degrees, on the shorter image axis; default 90), "lensradius" / "focaldistance"
//                         (a thin lens with a disk aperture, focus plane at that camera-space depth; default 0 / 1e6),
//                         "frameaspectratio" (default: the film's), "screenwindow" (default [-ratio, ratio] x [-1, 1]
//                         on the longer axis).
//   Camera "orthographic" "screenwindow", "frameaspectratio" as above in camera-space units, "lensradius" /
//                         "focaldistance" (pbrt's rule: rays from a point of the lens disk around the eye through the
//                         screen point moved to the focus plane).
//   Camera "spherical"    "mapping" "equalarea" (default) or "equirectangular" over the whole film.
//   Camera "realistic"    "lensfile" (pbrt's tabulated lens: per line radius, thickness, index of refraction and
//                         aperture diameter in mm, '#' comments; read through read_file_bytes), "aperturediameter"
//                         (mm, default 1; clamped to the stop's), "focusdistance" (m, default 10); "aperture" shapes
//                         other than the stop's circle are warned. Set up and traced by renderer/world/lens_system.h.
//   every camera          "shutteropen" / "shutterclose" (default 0 / 1; swapped with a warning when reversed, an
//                         error when equal): the shutter interval that Kiln's ray times [0, 1) span.
//   Film "rgb"            "xresolution" / "yresolution" (1280 x 720), "filename" (its stem names the EXR; default
//                         pbrt.exr), "cropwindow" (fractions x0 x1 y0 y1) or "pixelbounds": the image is the cropped
//                         region, as pbrt writes it; "iso" (100) times the exposure (shutterclose - shutteropen)
//                         over 100 scales the image (pbrt's imaging ratio); "diagonal" (mm, 35) sizes a realistic
//                         camera's film. "gbuffer" adds Kiln's AOV layers to the image; "spectral" is rendered as
//                         "rgb" (Kiln is an RGB renderer) with a warning.
//   Sampler               "pixelsamples" (16) -> samples per pixel; Kiln's own stratified sampler replaces pbrt's
//                         (a warning names the one the file asked for).
//   PixelFilter           box (radius 0.5), gaussian (radius 1.5, sigma 0.5; pbrt's default when the file has no
//                         PixelFilter), triangle (2), mitchell (2, B = C = 1/3) into CameraDesc::filter; "sinc" and
//                         different x / y radii are warned.
// The camera looks down +z of its space with +y up and +x to the right of the image (pbrt's left-handed camera
// space); the world-from-camera transform is the inverse of the transform in effect at the Camera directive, and
// CameraDesc::left_handed says whether it keeps that handedness (a mirrored camera transform flips the image the way
// pbrt flips it). A camera transform that moves over the shutter (ActiveTransform) makes CameraDesc::motion.
#pragma once
#include <functional>
#include <optional>
#include <string>

#include "core/transform.h"
#include "scenes/pbrt/diagnostics.h"
#include "scenes/pbrt/params.h"
#include "scenes/scene.h"

namespace kiln {

struct PbrtCameraInput {
  Transform camera_from_world;
  std::optional<Transform> camera_from_world_end;  // the transform at the end time when the camera moves
  float transform_start_time = 0.0f, transform_end_time = 1.0f;  // TransformTimes, in pbrt's time
  std::string camera_type = "perspective", film_type = "rgb", sampler_type = "zsobol", filter_type = "gaussian";
  PbrtParams camera, film, sampler, filter;  // empty lists for directives the file leaves out
  bool has_filter = false;                   // a PixelFilter directive was given
  bool has_sampler = false;
  // Turns a file name written in the Camera directive into a path (throws kiln::Error when it cannot be found).
  std::function<std::string(const std::string& name, int line)> resolve;
};

// The shutter interval in pbrt's time, and the map of pbrt times onto Kiln's ray times (0 at open, 1 at close).
struct PbrtShutter {
  float open = 0.0f, close = 1.0f;
  float to_kiln(float t) const { return (t - open) / (close - open); }
};

struct PbrtCamera {
  CameraDesc desc;
  PbrtShutter shutter;
};

PbrtCamera make_pbrt_camera(const PbrtCameraInput& in, PbrtDiagnostics& diag);

// pbrt's tabulated lens file (scenes/pbrt/camera.h, Camera "realistic") into interfaces in metres; `text` is the
// file's content. Throws kiln::Error naming the file and line of a row that is not four numbers.
std::vector<LensInterfaceDesc> parse_lens_file(const std::string& text, const std::string& path);

}  // namespace kiln
