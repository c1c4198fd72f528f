// pbrt-v4 shapes as Kiln geometry, in the shape's object space (the loader adds the transform, material, area
// light and orientation):
//   trianglemesh  "point3 P", "integer indices" (optional for a single triangle), "normal N", "point2 uv"
//   plymesh       "string filename" (.ply or gzip-compressed .ply.gz; resolved like Include), through the PLY loader
//   loopsubdiv    "integer levels" (default 3), "point3 P", "integer indices": MeshDesc::subdivide = levels, smooth
//   bilinearmesh  "point3 P", "integer indices" (4 per patch, p00 p10 p01 p11; optional for one patch), "normal N",
//                 "point2 uv": two triangles per patch (p00 p10 p11, p00 p11 p01), a warning when a patch is not planar
//   sphere        "float radius" (default 1); with "zmin" / "zmax" / "phimax" cut-aways a partial sphere (a quadric)
//   disk          "float radius" (1), "innerradius" (0), "height" (0), "phimax" (360): a quadric
//   cylinder      "float radius" (1), "zmin" (-1), "zmax" (1), "phimax" (360): a quadric
//   every shape   "alpha" (float or float texture): a cut-out (PbrtShapeContext::alpha reads it)
// cone, paraboloid and hyperboloid are pbrt-v3 shapes that pbrt-v4 dropped: warned and skipped, as are other shapes
// (curve, ...) and per-shape features Kiln does not render (displacement). Malformed data (an index out of range,
// counts that do not match, a radius that is not positive) is a kiln::Error naming file, line and shape.
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
  std::optional<QuadricDesc> quadric;
  // A "bilinearmesh" without "uv": pbrt's (u, v) of its patch corners per vertex ((0,0), (1,0), (0,1), (1,1)), when
  // no vertex is two different corners; empty otherwise. Only what reads them (an emission image) takes them: the
  // mesh's triangles otherwise keep the per-triangle default.
  std::vector<Vec2f> patch_uvs;
  bool empty() const { return !mesh && !sphere && !quadric; }
};

struct PbrtShapeContext {
  PbrtDiagnostics& diagnostics;
  // Turns a file name written in the scene into a path (throws kiln::Error when it cannot be found).
  std::function<std::string(const std::string& name, int line)> resolve;
  // The shape's "alpha" (PbrtBuilder::shape_alpha).
  std::function<ShapeAlphaDesc(const PbrtParams& ps)> alpha;
};

// The shape `type` described by `ps`; empty (with a warning) for shapes Kiln does not render.
PbrtShape make_pbrt_shape(const std::string& type, const PbrtParams& ps, const PbrtShapeContext& ctx);

}  // namespace kiln
