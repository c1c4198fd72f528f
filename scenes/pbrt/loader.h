// pbrt-v4 scene files (pbrt.org/fileformat-v4) as a Kiln SceneDesc. What is read, what is warned and how pbrt's
// conventions map onto Kiln's is listed in the README ("pbrt-v4"); in short:
//   * syntax: scenes/pbrt/tokenizer.h, typed parameter lists scenes/pbrt/params.h; Include and Import (world block;
//     its attribute changes stay inside the imported file) resolve against the including file's folder, then
//     against the main scene's folder (pbrt's own rule); ".gz" files are gunzipped;
//   * transforms LookAt, Translate, Scale, Rotate, Transform, ConcatTransform, Identity, CoordinateSystem /
//     CoordSysTransform ("camera" and "world" predefined), ActiveTransform (only the start transform is rendered;
//     motion is warned), AttributeBegin/End (TransformBegin/End read as pbrt-v4 reads them), Attribute defaults,
//     ReverseOrientation, ObjectBegin/End + ObjectInstance (meshes become Kiln instances of a shared prototype);
//   * camera, film, sampler and filter: scenes/pbrt/camera.h; Integrator "maxdepth" -> max_recursion_depth
//     (default 5; pbrt and Kiln count bounces alike);
//   * shapes: scenes/pbrt/shapes.h (meshes, spheres, the quadrics disk / cylinder / partial sphere into
//     SceneDesc::quadrics, "alpha" cut-outs: scenes/pbrt/alpha.cpp); materials into MaterialDesc::pbrt
//     (scenes/scene.h): diffuse, conductor, dielectric, thindielectric, coateddiffuse, coatedconductor,
//     diffusetransmission, interface; "mix" into MaterialDesc::mix, its components named by MakeNamedMaterial before
//     or after it (resolved at the end of the file); measured, hair and subsurface are warned and rendered as pbrt's
//     default diffuse; named materials; constant textures (others warned); spectra (named, inline, .spd files,
//     blackbody) by scenes/pbrt/spectrum.h;
//   * lights: AreaLightSource "diffuse" (L x scale, twosided) on meshes, spheres and quadrics, LightSource point,
//     spot, distant (from / to, pbrt's smoothstep spot falloff, "power" / "illuminance" as pbrt normalises them) and
//     infinite with a constant L (SceneDesc::infinite_lights) or an equal-area image "filename"
//     (SceneDesc::env_lights, in the light's frame);
//   * media: MakeNamedMedium into SceneDesc::media (scenes/pbrt/media.cpp), MediumInterface on shapes and the
//     camera (names resolved when the file ends, so a medium may be named before it is defined).
// Anything else the file asks for is a warning naming file, line and directive (SceneDesc::warnings) and, when it
// changes the picture, a SceneDesc::unsupported entry. Malformed input throws kiln::Error naming the file and line.
// SceneDesc::rules stays SceneRules::Kiln.
#pragma once
#include <string>

#include "scenes/scene.h"

namespace kiln {

// pbrt's default Integrator maxdepth.
inline constexpr int kPbrtDefaultMaxDepth = 5;
// Nesting limit for Include / Import (a file that includes itself would otherwise recurse without end).
inline constexpr int kPbrtMaxIncludeDepth = 32;

struct PbrtOptions {
  // A PLY mesh or included file that cannot be found is a warning (the shape or file is left out) instead of an
  // error: for surveying a scene collection whose large files are not at hand (kiln info --allow-missing).
  bool allow_missing_files = false;
};

SceneDesc load_pbrt(const std::string& path, const PbrtOptions& options = {});
// Parses `text` as though it were the file `path` (its Include, Import and mesh files resolve against that folder).
SceneDesc parse_pbrt(std::string text, const std::string& path, const PbrtOptions& options = {});

}  // namespace kiln
