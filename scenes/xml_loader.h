// CENG795 (METU "Advanced Ray Tracing", 2017-2021) XML scene loader; the format is specified in
// shared/docs/ceng795-scene-format.md. Fills SceneDesc only; no rendering decisions are taken here except the
// format's own conventions:
//  - indices are 1-based unless <ZeroBasedIndexing>true; vertexOffset/textureOffset are added; Sphere Center is a
//    vertex index (also subject to ZeroBasedIndexing);
//  - inline meshes get their own compacted vertex arrays (MeshDesc indices are 0-based into MeshDesc::positions);
//    a face index i names vertex i + vertexOffset and TexCoordData entry i + textureOffset (both offsets default
//    to 0, so without offsets entry k is the uv of vertex k); uvs are attached when every vertex of the mesh has
//    one (an out-of-range entry is an error only when textureOffset is given);
//  - transformation tokens "t1 r2 s3 c1" apply first-token-first: M = T_last ... T_1;
//  - MeshInstance: resetTransform=true -> M_inst, false (default) -> M_inst * M_base; the base MeshDesc is marked
//    is_instance_base and stays visible; an instance without <Material> uses the base mesh's;
//  - material kind: the type attribute (mirror/dielectric/conductor) when given, else Plain; the 2019 inference
//    (non-zero Transparency / MirrorReflectance) is build_material's job (scenes/material_mapping.h);
//  - Material and BRDF ids are resolved to indices into SceneDesc::materials / SceneDesc::brdfs (BRDF ids share
//    one id space across the five kinds);
//  - relative plyFile/binaryFile/texture paths are relative to the XML file's directory;
//  - unknown elements and tolerated oddities (a 5-number NearPlane) go to SceneDesc::warnings; stray text inside
//    container elements is ignored.
// Bad input (unreadable file, malformed XML, dangling id, bad number, wrong count, missing required element) is a
// kiln::Error "FILE: line N (Element path): problem".
#pragma once
#include <string>

#include "scenes/scene.h"

namespace kiln {

SceneDesc load_ceng795_xml(const std::string& path);

}  // namespace kiln
