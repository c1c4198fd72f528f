// Environment maps of a scene (SceneDesc::env_lights) as ImageInfiniteLights: the image read (EXR directly, other
// formats through the OpenImageIO plugin), its format resolved (a pbrt-v4 equal-area map that is not square but
// 2:1 is read as pbrt-v3's lat-long, with a warning), pbrt's "scale" and "illuminance" applied.
//
// "illuminance" E follows pbrt-v4 (lights.cpp, ImageInfiniteLight creation): k = the sum, over the texels whose
// direction has z > 0 in the map's frame, of luminance x cos(theta), times 2 pi / (texel count); the map is scaled by
// E / k. A texel of the equal-area square spans 4 pi / (texel count), so k is half the illuminance the map gives a
// surface facing +z, and the scaled map gives 2 E; Kiln reproduces pbrt's images rather than the parameter's name.
// Lat-long maps use the same rule over their texels' solid angles (texel solid angle / 2 in place of 2 pi / count).
#pragma once
#include <string>
#include <vector>

#include "lights/image_infinite_light.h"
#include "scenes/scene.h"

namespace kiln {

// Throws kiln::Error naming the scene file and the element when the image cannot be read, is empty, or has a
// shape its format does not allow. Warnings (a non-square map read as lat-long) are appended to `warnings`.
ImageInfiniteLight make_environment_light(const SceneDesc& scene, const EnvLightDesc& env, float scene_radius,
                                          EnvMapSampling sampling, std::vector<std::string>& warnings);

// pbrt-v4's illuminance normaliser k of an image in a layout (see above); 0 when the upper hemisphere is black.
double pbrt_map_illuminance(const Image& image, EnvMapLayout layout);

// The linear map from the course's lat-long frame (y up) to pbrt-v3's (z up, phi from +x towards +y): a lat-long
// texel (u, v) is the course direction d and pbrt-v3's direction C d. It mirrors (det C = -1).
Transform course_to_pbrt_lat_long();

}  // namespace kiln
