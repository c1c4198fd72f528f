// Bad CENG795 XML input: every case is a kiln::Error whose message names the file, the line and element, and the
// problem; never a crash, never a silently wrong scene.
#include <gtest/gtest.h>

#include "scenes/xml_loader.h"
#include "xml_test_util.h"

namespace kiln {
namespace {

using xml_test::error_of;
using xml_test::SceneText;
using xml_test::write_tmp;

struct BadCase {
  const char* name;
  std::string xml;
  std::string expect;  // substring of the message after "FILE: "
};

// Replaces the first occurrence of `from` in the valid scene text.
std::string edit(const std::string& from, const std::string& to, SceneText s = {}) {
  std::string x = s.str();
  const size_t at = x.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? x : x.replace(at, from.size(), to);
}

SceneText with_objects(const std::string& objects, const std::string& top = "") {
  SceneText s;
  s.objects = "\n  <Objects>\n    " + objects + "\n  </Objects>";
  s.top = top;
  return s;
}

void expect_error(const BadCase& c) {
  const std::string path = write_tmp(std::string("bad/") + c.name + ".xml", c.xml);
  const std::string msg = error_of([&] { load_ceng795_xml(path); });
  EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << c.name << ": message does not start with the file: " << msg;
  EXPECT_NE(msg.find(c.expect), std::string::npos) << c.name << ": expected '" << c.expect << "' in: " << msg;
}

TEST(XmlErrors, MissingFileAndMalformedXml) {
  const std::string missing = xml_test::tmp_dir().string() + "/does_not_exist.xml";
  EXPECT_NE(error_of([&] { load_ceng795_xml(missing); }).find(missing + ": cannot open file"), std::string::npos);
  expect_error({"malformed", "<Scene>\n  <Cameras>\n    <Camera id=\"1\">\n  </Cameras>\n</Scene>\n",
                "line 4: malformed XML: Start-end tags mismatch"});
  expect_error({"unclosed_attr", "<Scene>\n<Camera id=\"1>\n</Scene>", "malformed XML"});
  expect_error({"empty", "", "malformed XML: No document element found"});
  expect_error({"wrong_root", "<Scenes></Scenes>", "root element is <Scenes>, expected <Scene>"});
}

TEST(XmlErrors, DanglingIds) {
  const BadCase cases[] = {
      {"dangling_material", with_objects("<Mesh id=\"1\"><Material>2</Material><Faces>1 2 3</Faces></Mesh>").str(),
       "line 26 (Objects / Mesh id=1 / Material): Material 2 is not defined"},
      {"dangling_brdf", edit("<Material id=\"1\">", "<Material id=\"1\" BRDF=\"4\">"),
       "(Materials / Material id=1): BRDF 4 is not defined"},
      {"dangling_transform",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces>"
                    "<Transformations>t1 r2</Transformations></Mesh>",
                    "<Transformations><Translation id=\"1\">0 0 1</Translation></Transformations>")
           .str(),
       "(Objects / Mesh id=1 / Transformations): 'r2' refers to Rotation id=2, which is not defined"},
      {"bad_token",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces>"
                    "<Transformations>x1</Transformations></Mesh>")
           .str(),
       "bad transformation token 'x1'"},
      {"bad_token_no_id",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces>"
                    "<Transformations>t</Transformations></Mesh>")
           .str(),
       "bad transformation token 't'"},
      {"dangling_base_mesh", with_objects("<MeshInstance id=\"1\" baseMeshId=\"3\"/>").str(),
       "(Objects / MeshInstance id=1): baseMeshId 3 is not a defined Mesh id"},
      {"base_is_light_mesh",
       with_objects("<LightMesh id=\"1\"><Radiance>1 1 1</Radiance><Faces>1 2 3</Faces></LightMesh>"
                    "<MeshInstance id=\"1\" baseMeshId=\"1\"/>")
           .str(),
       "baseMeshId 1 is not a defined Mesh id"},
      {"ambiguous_base_mesh",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>"
                    "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>"
                    "<MeshInstance id=\"1\" baseMeshId=\"1\"/>")
           .str(),
       "baseMeshId 1 is ambiguous"},
      {"face_index_out_of_range",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>\n1 2 3\n2 3 5</Faces></Mesh>").str(),
       "(Objects / Mesh id=1 / Faces): triangle 2: vertex index 5 is out of range: VertexData has 4 vertices "
       "(1-based indices)"},
      {"face_index_zero", with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>0 1 2</Faces></Mesh>").str(),
       "vertex index 0 is out of range"},
      {"vertex_offset_out_of_range",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces vertexOffset=\"2\">1 2 3</Faces></Mesh>").str(),
       "vertex index 3 (+ vertexOffset 2) is out of range"},
      {"triangle_index",
       with_objects("<Triangle id=\"1\"><Material>1</Material><Indices>1 2 9</Indices></Triangle>").str(),
       "(Objects / Triangle id=1 / Indices): triangle 1: vertex index 9 is out of range"},
      {"center_index",
       with_objects("<Sphere id=\"1\"><Material>1</Material><Center>5</Center><Radius>1</Radius></Sphere>").str(),
       "(Objects / Sphere id=1 / Center): vertex index 5 is out of range"},
      {"texture_id",
       with_objects("<Sphere id=\"1\"><Material>1</Material><Texture>2</Texture><Center>1</Center><Radius>1</Radius>"
                    "</Sphere>")
           .str(),
       "(Objects / Sphere id=1 / Texture): texture 2 is not defined"},
      {"texture_offset_out_of_range",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces textureOffset=\"1\">1 2 3</Faces></Mesh>",
                    "<TexCoordData>0 0 1 0 1 1</TexCoordData>")
           .str(),
       "texture coordinate index 3 (+ textureOffset 1) is out of range: TexCoordData has 3 entries"},
      {"env_image_id",
       edit("<BackgroundColor>0 0 0</BackgroundColor>",
            "<Lights><SphericalDirectionalLight id=\"1\"><ImageId>4</ImageId></SphericalDirectionalLight></Lights>"),
       "(Lights / SphericalDirectionalLight id=1 / ImageId): Image 4 is not defined"},
  };
  for (const auto& c : cases) expect_error(c);
}

TEST(XmlErrors, BadNumbersAndCounts) {
  const BadCase cases[] = {
      {"abc", edit("<Position>0 0 10</Position>", "<Position>0 abc 10</Position>"),
       "line 5 (Cameras / Camera id=1 / Position): expected a number, got 'abc'"},
      {"overflow", edit("<Position>0 0 10</Position>", "<Position>0 1e999 10</Position>"), "'1e999' is out of range"},
      {"nan", edit("<Position>0 0 10</Position>", "<Position>nan 0 10</Position>"), "'nan' is not a finite number"},
      {"inf_colour",
       edit("<DiffuseReflectance>1 1 1</DiffuseReflectance>", "<DiffuseReflectance>1 inf 1</DiffuseReflectance>"),
       "(Materials / Material id=1 / DiffuseReflectance): 'inf' is not a finite number"},
      {"two_numbers", edit("<Gaze>0 0 -1</Gaze>", "<Gaze>0 -1</Gaze>"), "expected 3 numbers, got 2"},
      {"vertex_data_count", edit("1 0 0\n", "1 0\n"), "(VertexData): has 11 numbers, not a multiple of 3"},
      {"vertex_data_line", edit("1 1 0\n", "1 x 0\n"), "line 22 (VertexData): expected a number, got 'x'"},
      {"faces_count", with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3 4</Faces></Mesh>").str(),
       "(Objects / Mesh id=1 / Faces): has 4 indices, not a multiple of 3"},
      {"faces_float", with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3.5</Faces></Mesh>").str(),
       "expected an integer, got '3.5'"},
      {"bad_id", edit("<Material id=\"1\">", "<Material id=\"one\">"),
       "(Materials / Material id=one @id): expected an integer, got 'one'"},
      {"bad_bool", edit("<BackgroundColor>0 0 0</BackgroundColor>", "<ZeroBasedIndexing>yes</ZeroBasedIndexing>"),
       "expected true or false, got 'yes'"},
      {"near_plane_short", edit("<NearPlane>-1 1 -1 1</NearPlane>", "<NearPlane>-1 1 -1</NearPlane>"),
       "(Cameras / Camera id=1 / NearPlane): expected 4 numbers (left right bottom top), got 3"},
      {"resolution", edit("<ImageResolution>16 8</ImageResolution>", "<ImageResolution>16 0</ImageResolution>"),
       "image resolution must be positive"},
      {"num_samples",
       edit("<ImageName>out.png</ImageName>", "<ImageName>out.png</ImageName><NumSamples>0</NumSamples>"),
       "NumSamples must be at least 1"},
      {"radius",
       with_objects("<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>-1</Radius></Sphere>").str(),
       "Radius must be positive"},
      {"zero_scaling",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>",
                    "<Transformations><Scaling id=\"1\">1 0 1</Scaling></Transformations>")
           .str(),
       "(Transformations / Scaling id=1): scaling by zero is not invertible"},
      {"rotation_count",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>",
                    "<Transformations><Rotation id=\"1\">90 0 1</Rotation></Transformations>")
           .str(),
       "(Transformations / Rotation id=1): expected 4 numbers, got 3"},
      {"singular_composite",
       with_objects(
           "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>",
           "<Transformations><Composite id=\"1\">0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 1</Composite></Transformations>")
           .str(),
       "(Transformations / Composite id=1): transformation matrix is singular"},
  };
  for (const auto& c : cases) expect_error(c);
}

TEST(XmlErrors, MissingRequiredElementsAndBadValues) {
  const BadCase cases[] = {
      {"no_resolution", edit("<ImageResolution>16 8</ImageResolution>", ""),
       "line 4 (Cameras / Camera id=1): missing <ImageResolution>"},
      {"no_gaze", edit("<Gaze>0 0 -1</Gaze>", ""), "missing <Gaze> (or <GazePoint>)"},
      {"no_position", edit("<Position>0 0 10</Position>", ""), "missing <Position>"},
      {"no_image_name", edit("<ImageName>out.png</ImageName>", ""), "missing <ImageName>"},
      {"no_near_plane", edit("<NearPlane>-1 1 -1 1</NearPlane>", ""), "missing <NearPlane> (or <FovY>)"},
      {"up_parallel", edit("<Up>0 1 0</Up>", "<Up>0 0 2</Up>"), "Up is zero or parallel to the gaze direction"},
      {"camera_type", edit("<Camera id=\"1\">", "<Camera id=\"1\" type=\"fisheye\">"), "unknown camera type 'fisheye'"},
      {"duplicate_child", edit("<Gaze>0 0 -1</Gaze>", "<Gaze>0 0 -1</Gaze><Gaze>0 0 -1</Gaze>"), "duplicate <Gaze>"},
      {"renderer", edit("<ImageName>out.png</ImageName>", "<ImageName>out.png</ImageName><Renderer>Photons</Renderer>"),
       "unsupported renderer 'Photons' (only PathTracing)"},
      {"renderer_param",
       edit("<ImageName>out.png</ImageName>",
            "<ImageName>out.png</ImageName><Renderer>PathTracing</Renderer><RendererParams>MIS</RendererParams>"),
       "unknown renderer parameter 'MIS'"},
      {"no_material", with_objects("<Mesh id=\"1\"><Faces>1 2 3</Faces></Mesh>").str(),
       "(Objects / Mesh id=1): missing <Material>"},
      {"no_faces", with_objects("<Mesh id=\"1\"><Material>1</Material></Mesh>").str(), "missing <Faces>"},
      {"no_mesh_id", with_objects("<Mesh><Material>1</Material><Faces>1 2 3</Faces></Mesh>").str(),
       "(Objects / Mesh): missing id attribute"},
      {"shading_mode",
       with_objects("<Mesh id=\"1\" shadingMode=\"phong\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>").str(),
       "shadingMode must be flat or smooth, got 'phong'"},
      {"interpolation_2019",
       with_objects("", "<Textures><Texture id=\"1\"><ImageName>a.png</ImageName>"
                        "<Interpolation>bicubic</Interpolation></Texture></Textures>").str(),
       "(Textures / Texture id=1 / Interpolation): unknown Interpolation 'bicubic' (expected nearest, bilinear, "
       "trilinear, ewa)"},
      {"interpolation_2021",
       with_objects("", "<Textures><Images><Image id=\"1\">a.png</Image></Images><TextureMap id=\"2\" type=\"image\">"
                        "<ImageId>1</ImageId><Interpolation>EWA</Interpolation></TextureMap></Textures>").str(),
       "(Textures / TextureMap id=2 / Interpolation): unknown Interpolation 'EWA'"},
      {"material_type", edit("<Material id=\"1\">", "<Material id=\"1\" type=\"glass\">"),
       "unknown material type 'glass'"},
      {"duplicate_material", edit("</Material>", "</Material><Material id=\"1\"></Material>"),
       "duplicate Material id 1"},
      {"light_mesh_radiance",
       with_objects("<LightMesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></LightMesh>").str(),
       "(Objects / LightMesh id=1): missing <Radiance>"},
      {"area_light_form",
       edit("<BackgroundColor>0 0 0</BackgroundColor>",
            "<Lights><AreaLight id=\"1\"><Position>0 0 0</Position><Radiance>1 1 1</Radiance></AreaLight></Lights>"),
       "missing <Normal> and <Size> (or <EdgeVector1> and <EdgeVector2>)"},
      {"point_light_intensity",
       edit("<BackgroundColor>0 0 0</BackgroundColor>",
            "<Lights><PointLight id=\"1\"><Position>0 0 0</Position></PointLight></Lights>"),
       "(Lights / PointLight id=1): missing <Intensity>"},
      {"spot_angles",
       edit("<BackgroundColor>0 0 0</BackgroundColor>",
            "<Lights><SpotLight id=\"1\"><Position>0 0 0</Position><Direction>0 -1 0</Direction>"
            "<Intensity>1 1 1</Intensity><CoverageAngle>20</CoverageAngle><FalloffAngle>30</FalloffAngle>"
            "</SpotLight></Lights>"),
       "FalloffAngle must not exceed CoverageAngle"},
      {"directional_zero",
       edit("<BackgroundColor>0 0 0</BackgroundColor>",
            "<Lights><DirectionalLight id=\"1\"><Direction>0 0 0</Direction><Radiance>1 1 1</Radiance>"
            "</DirectionalLight></Lights>"),
       "vector must not be zero"},
      {"brdf_exponent",
       edit("<BackgroundColor>0 0 0</BackgroundColor>", "<BRDFs><ModifiedPhong id=\"1\"></ModifiedPhong></BRDFs>"),
       "(BRDFs / ModifiedPhong id=1): missing <Exponent>"},
      {"duplicate_brdf",
       edit("<BackgroundColor>0 0 0</BackgroundColor>",
            "<BRDFs><ModifiedPhong id=\"1\"><Exponent>1</Exponent></ModifiedPhong>"
            "<TorranceSparrow id=\"1\"><Exponent>1</Exponent></TorranceSparrow></BRDFs>"),
       "duplicate BRDF id 1"},
      {"duplicate_scalar",
       edit("<BackgroundColor>0 0 0</BackgroundColor>",
            "<BackgroundColor>0 0 0</BackgroundColor><BackgroundColor>1 1 1</BackgroundColor>"),
       "duplicate <BackgroundColor>"},
      {"aperture_without_focus",
       edit("<ImageName>out.png</ImageName>", "<ImageName>out.png</ImageName><ApertureSize>1</ApertureSize>"),
       "ApertureSize needs a <FocusDistance>"},
      {"integrator_params_alone",
       edit("<BackgroundColor>0 0 0</BackgroundColor>", "<IntegratorParams>ImportanceSampling</IntegratorParams>"),
       "IntegratorParams without an <Integrator>"},
  };
  for (const auto& c : cases) expect_error(c);
}

TEST(XmlErrors, BadReferencedFiles) {
  write_tmp("bad/files/ply/truncated.ply",
            "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                std::string(20, '\0'));
  write_tmp("bad/files/ply/bad_index.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  write_tmp("bad/files/short.bin", std::string("\x05\x00\x00\x00\x00\x00\x00\x00", 8));
  const BadCase cases[] = {
      {"files/missing_ply",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"ply/nope.ply\"/></Mesh>").str(),
       "(Objects / Mesh id=1 / Faces): plyFile 'ply/nope.ply': "},
      {"files/truncated_ply",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"ply/truncated.ply\"/></Mesh>").str(),
       "plyFile 'ply/truncated.ply': "},
      {"files/bad_index_ply",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"ply/bad_index.ply\"/></Mesh>").str(),
       "bad_index.ply: line 13 (element 'face' #0): vertex index 3 is out of range (3 vertices)"},
      {"files/short_vertex_bin", edit(xml_test::kVertices, "<VertexData binaryFile=\"short.bin\"/>"),
       "(VertexData): binaryFile 'short.bin' is truncated: 5 entries need 64 bytes, file has 8"},
      {"files/short_faces_bin",
       with_objects("<Mesh id=\"1\"><Material>1</Material><Faces binaryFile=\"short.bin\"/></Mesh>").str(),
       "binaryFile 'short.bin' is truncated: 5 triangles need 64 bytes, file has 8"},
      {"files/missing_bin", edit(xml_test::kVertices, "<VertexData binaryFile=\"none.bin\"/>"),
       "binaryFile 'none.bin': "},
  };
  for (const auto& c : cases) expect_error(c);
  // The PLY's own message is kept inside the XML one.
  const std::string path = write_tmp("bad/files/trunc_msg.xml", cases[1].xml);
  EXPECT_NE(error_of([&] { load_ceng795_xml(path); }).find("truncated.ply: element 'vertex': file is truncated"),
            std::string::npos);
}

}  // namespace
}  // namespace kiln
