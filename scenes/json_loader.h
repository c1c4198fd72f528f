// CS171 (ShanghaiTech, Fall 2022) "Assignment 4: Global Illumination" JSON scene configs
// (see shared/docs/cs171-gi-config-format.md). Every key the course skeleton reads is required here too:
//
//   spp               int > 0          -> CameraDesc::num_samples
//   max_depth         int >= 1         -> SceneDesc::max_recursion_depth = max_depth. CS171 counts the path
//                                         vertices that gather direct light; Kiln's path tracer counts bounces
//                                         after the camera ray and samples lights at depths 0..max-1, which is
//                                         the same number of vertices.
//   image_resolution  [w, h] ints > 0  -> CameraDesc::width / height
//   cam_config        position, look_at, ref_up [3]; vertical_fov (full, degrees); focal_length > 0
//                     -> pinhole CameraDesc with use_fov. The skeleton scales the image plane by focal_length but
//                     keeps it at distance 1, so fov_y = 2 atan(focal_length tan(vertical_fov / 2)).
//   light_config      position (centre), size [x extent, z extent], radiance [3]
//                     -> a two-triangle emissive MeshDesc facing -Y (geometric normal (v1-v0)x(v2-v0) points
//                     down, one-sided), with a black Lambert material; no AreaLightDesc.
//   materials[]       name, type, color [3]:
//                       "diffuse"     -> Plain, Lambert BRDF (shared SceneDesc::brdfs entry), diffuse = color
//                       "specular"    -> Mirror, mirror = color (default 1 when color is absent)
//                       "translucent" -> Dielectric, refraction_index = `ior` (a Kiln extension, default 1.5);
//                                        color is optional and ignored (Kiln's dielectric is clear)
//   objects[]         obj_file_path (relative to the config file's folder), material_name, translate [3],
//                     scale (uniform, > 0), has_bvh (bool, speed hint only, ignored)
//                     -> MeshDesc from load_obj with to_world = translate * scale.
//
// Unknown keys, and extra array elements (the skeleton reads only the first N), are reported in
// SceneDesc::warnings with their key path. Missing keys, wrong types, unknown material types, duplicate or
// dangling material names and unloadable OBJ files throw kiln::Error("FILE: key.path: what").
// The camera renders with PathTracing + next-event estimation + cosine importance sampling (what the course
// framework does), outputs "<config stem>.exr", and SceneDesc::png_gamma_encode is set (pure gamma 2.2 PNG).
#pragma once
#include <string>

#include "scenes/scene.h"

namespace kiln {

SceneDesc load_cs171_json(const std::string& path);

}  // namespace kiln
