// pbrt-v4's camera, film, sampler and pixel filter as one Kiln CameraDesc.
//   Camera "perspective"  "fov" (degrees, on the shorter image axis; default 90), "lensradius" / "focaldistance"
//                         (a thin lens with a disk aperture, focus plane at that camera-space depth; default 0 / 1e6),
//                         "frameaspectratio", "screenwindow". Other camera types are an error (no stand-in would
//                         render the same picture).
//   Film "rgb"            "xresolution" / "yresolution" (1280 x 720), "filename" (its stem names the EXR; default
//                         pbrt.exr), "cropwindow" (fractions x0 x1 y0 y1) or "pixelbounds": the image is the cropped
//                         region, as pbrt writes it. "gbuffer" and "spectral" films are read as "rgb" with a warning.
//   Sampler               "pixelsamples" (16) -> samples per pixel; Kiln's own stratified sampler replaces pbrt's
//                         (a warning names the one the file asked for).
//   PixelFilter           box (radius 0.5), gaussian (radius 1.5, sigma 0.5; pbrt's default when the file has no
//                         PixelFilter), triangle (2), mitchell (2, B = C = 1/3) into CameraDesc::filter; "sinc" and
//                         different x / y radii are warned.
// The camera looks down +z of its space with +y up and +x to the right of the image (pbrt's left-handed camera
// space); the world-from-camera transform is the inverse of the transform in effect at the Camera directive, and
// CameraDesc::left_handed says whether it keeps that handedness (a mirrored camera transform flips the image the way
// pbrt flips it).
#pragma once
#include <string>

#include "core/transform.h"
#include "scenes/pbrt/diagnostics.h"
#include "scenes/pbrt/params.h"
#include "scenes/scene.h"

namespace kiln {

struct PbrtCameraInput {
  Transform camera_from_world;
  std::string camera_type = "perspective", film_type = "rgb", sampler_type = "zsobol", filter_type = "gaussian";
  PbrtParams camera, film, sampler, filter;  // empty lists for directives the file leaves out
  bool has_filter = false;                   // a PixelFilter directive was given
  bool has_sampler = false;
};

CameraDesc make_pbrt_camera(const PbrtCameraInput& in, PbrtDiagnostics& diag);

}  // namespace kiln
