// Stanford PLY triangle-mesh loader: ASCII, binary little- and big-endian; every scalar type (char/uchar/short/
// ushort/int/uint/float/double and the int8/uint8/.../float32/float64 spellings); list properties with any integer
// count and index types. Reads the "vertex" element (x y z; optional nx ny nz; optional uv as u v / s t /
// texture_u texture_v / texture_s texture_t) and the "face" element's vertex_indices (or vertex_index) list;
// polygons are triangulated as a fan. Other elements and properties are skipped.
// Every count and index is validated against the file: a truncated file, a face with fewer than 3 vertices, a
// negative or out-of-range index, a non-finite coordinate is a kiln::Error naming the file and the element.
// Binary files are decoded from one in-memory buffer with per-property column loops (no per-vertex allocation or
// per-value dispatch) and a fast path for the common float x y z + uchar/int triangle layout.
#pragma once
#include <string>
#include <string_view>

#include "scenes/scene.h"

namespace kiln {

// Loads a PLY file; MeshDesc::name is the file name (without directories).
MeshDesc load_ply(const std::string& path);

// Parses PLY data already in memory; `file` names it in error messages and becomes MeshDesc::name.
MeshDesc parse_ply(std::string_view data, const std::string& file);

}  // namespace kiln
