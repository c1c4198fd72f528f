// pbrt-v4 shapes as Kiln geometry, in the shape's object space (the loader adds the transform, material, area
// light and orientation):
//   trianglemesh  "point3 P", "integer indices" (optional for a single triangle), "normal N", "point2 uv"
//   plymesh       "string filename" (.ply or gzip-compressed .ply.gz; resolved like Include), through the PLY loader
//   loopsubdiv    "integer levels" (default 3), "point3 P", "integer indices": MeshDesc::subdivide = levels, smooth
//   bilinearmesh  "point3 P", "integer indices" (4 per patch, p00 p10 p01 p11; optional for one patch), "normal N",
//                 "point2 uv": two triangles per patch (p00 p10 p11, p00 p11 p01), a warning when a patch is not planar
//   sphere        "float radius" (default 1); zmin / zmax / phimax cut-aways are warned and the full sphere is kept
// Other shapes (disk, cylinder, curve, ...) and per-shape features Kiln does not render (alpha cut-outs, displacement)
// are warnings. Malformed data (an index out of range, counts that do not match) is a kiln::Error naming file, line
// and shape.
#pragma once
#include <functional>
#include <optional>
#include <string>

#include "scenes/pbrt/diagnostics.h"
#include "scenes/pbrt/params.h"
#include "scenes/scene.h"

namespace kiln {

// A bilinear patch whose fourth corner lies further than this fraction of its diagonal from the plane of the other
// three is reported as non-planar (its two triangles then differ from pbrt's curved patch).
inline constexpr float kBilinearPlanarityTolerance = 1e-3f;

struct PbrtShape {
  std::optional<MeshDesc> mesh;
  std::optional<SphereDesc> sphere;
  bool empty() const { return !mesh && !sphere; }
};

struct PbrtShapeContext {
  PbrtDiagnostics& diagnostics;
  // Turns a file name written in the scene into a path (throws kiln::Error when it cannot be found).
  std::function<std::string(const std::string& name, int line)> resolve;
};

// The shape `type` described by `ps`; empty (with a warning) for shapes Kiln does not render.
PbrtShape make_pbrt_shape(const std::string& type, const PbrtParams& ps, const PbrtShapeContext& ctx);

}  // namespace kiln
