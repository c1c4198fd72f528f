// Wavefront OBJ meshes through tinyobjloader, as one MeshDesc in object space.
//
// - Polygons are triangulated by tinyobjloader (quads split along the shorter diagonal, larger polygons by ear
//   clipping); the polygon's winding is kept.
// - Vertices are de-duplicated by their (v, vt, vn) index triple. MeshDesc::normals / uvs are filled only when
//   every face vertex references a `vn` / `vt`; otherwise they are left empty and the renderer uses face normals.
// - Orientation comes from `vn`, not from winding: when normals are present, a triangle whose geometric normal
//   (v1-v0)x(v2-v0) points away from the average of its three vertex normals has its winding flipped, so geometric
//   and shading normals agree. (The CS171 walls and boxes are wound against their normals.)
// - Face indices are validated before tinyobjloader sees them (it silently accepts out-of-range indices):
//   0, non-integers and indices outside the elements defined so far are errors naming the line. Negative
//   indices are relative to the elements defined before the face, as the OBJ spec says.
// - `mtllib` / `usemtl`, groups, smoothing groups, lines and points are ignored: materials come from the caller.
#pragma once
#include <string>
#include <string_view>

#include "scenes/scene.h"

namespace kiln {

// Throws kiln::Error ("FILE: line N: what") for a missing or unreadable file, malformed or out-of-range face
// indices, malformed vertex lines, or a file without faces.
MeshDesc load_obj(const std::string& path);

// Same, from OBJ text already in memory; source_name is used in messages and as the mesh name.
MeshDesc parse_obj(std::string_view text, const std::string& source_name);

}  // namespace kiln
