// CENG795 XML loader on small hand-written scenes: transform order, instances, id -> index mapping, every camera,
// light, material and BRDF form, offsets and zero-based indexing, binary data files, tolerated oddities and the
// unsupported-feature record.
#include "scenes/xml_loader.h"

#include <gtest/gtest.h>

#include <cstring>

#include "xml_test_util.h"

namespace kiln {
namespace {

using xml_test::SceneText;
using xml_test::write_tmp;

SceneDesc load_text(const std::string& name, const std::string& xml) { return load_ceng795_xml(write_tmp(name, xml)); }

void expect_near(Vec3f a, Vec3f b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Tokens apply first-token-first: "t1 s1" translates then scales (M = S * T), "s1 t1" the reverse.
TEST(XmlLoader, TransformationTokensApplyFirstTokenFirst) {
  SceneText s;
  s.top = R"(
  <Transformations>
    <Translation id="1">1 0 0</Translation>
    <Scaling id="1">2 2 2</Scaling>
    <Rotation id="1">90 0 0 1</Rotation>
    <Composite id="1">1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1</Composite>
  </Transformations>)";
  s.objects = R"(
  <Objects>
    <Mesh id="1"><Material>1</Material><Faces>1 2 3</Faces><Transformations>t1 s1</Transformations></Mesh>
    <Mesh id="2"><Material>1</Material><Faces>1 2 3</Faces><Transformations>s1 t1</Transformations></Mesh>
    <Mesh id="3"><Material>1</Material><Faces>1 2 3</Faces><Transformations> r1   t1 </Transformations></Mesh>
    <Mesh id="4"><Material>1</Material><Faces>1 2 3</Faces><Transformations>c1</Transformations></Mesh>
    <Mesh id="5"><Material>1</Material><Faces>1 2 3</Faces></Mesh>
  </Objects>)";
  const SceneDesc d = load_text("transform_order.xml", s.str());
  ASSERT_EQ(d.meshes.size(), 5u);
  expect_near(d.meshes[0].to_world.point({0, 0, 0}), {2, 0, 0});
  expect_near(d.meshes[1].to_world.point({0, 0, 0}), {1, 0, 0});
  expect_near(d.meshes[2].to_world.point({1, 0, 0}), {1, 1, 0});  // rotate (1,0,0) -> (0,1,0), then translate
  expect_near(d.meshes[3].to_world.point({0, 0, 0}), {5, 6, 7});  // Composite is row-major
  EXPECT_TRUE(d.meshes[4].to_world.is_identity());
  // Positions stay in object space.
  EXPECT_EQ(d.meshes[0].positions[1], Vec3f(1, 0, 0));
}

TEST(XmlLoader, MeshInstancesResolveTransformsAndMaterials) {
  SceneText s;
  s.top = R"(
  <Transformations>
    <Translation id="1">0 0 3</Translation>
    <Scaling id="1">2 2 2</Scaling>
  </Transformations>)";
  s.materials = R"(
  <Materials>
    <Material id="7"><DiffuseReflectance>1 0 0</DiffuseReflectance></Material>
    <Material id="3"><DiffuseReflectance>0 1 0</DiffuseReflectance></Material>
  </Materials>)";
  s.objects = R"(
  <Objects>
    <MeshInstance id="1" baseMeshId="2" resetTransform="false"><Transformations>s1</Transformations></MeshInstance>
    <Sphere id="2"><Material>3</Material><Center>1</Center><Radius>1</Radius></Sphere>
    <Mesh id="2"><Material>7</Material><Faces>1 2 3 1 3 4</Faces><Transformations>t1</Transformations></Mesh>
    <MeshInstance id="2" baseMeshId="2" resetTransform="true" shadingMode="smooth">
      <Material>3</Material><Transformations>s1</Transformations>
    </MeshInstance>
    <MeshInstance id="3" baseMeshId="2"/>
  </Objects>)";
  const SceneDesc d = load_text("instances.xml", s.str());
  ASSERT_EQ(d.meshes.size(), 1u);
  ASSERT_EQ(d.instances.size(), 3u);
  EXPECT_TRUE(d.meshes[0].is_instance_base);
  EXPECT_TRUE(d.meshes[0].visible);
  EXPECT_EQ(d.meshes[0].material, 0);  // Material id=7 is the first material -> index 0
  EXPECT_EQ(d.spheres[0].material, 1);
  // resetTransform=false: M_inst * M_base = scale(2) * translate(0 0 3).
  expect_near(d.instances[0].to_world.point({0, 0, 0}), {0, 0, 6});
  EXPECT_EQ(d.instances[0].material, 0);  // inherited from the base mesh
  EXPECT_FALSE(d.instances[0].smooth.has_value());
  // resetTransform=true: only the instance's own transform.
  expect_near(d.instances[1].to_world.point({0, 0, 1}), {0, 0, 2});
  EXPECT_EQ(d.instances[1].material, 1);
  EXPECT_EQ(d.instances[1].smooth, std::optional<bool>(true));
  // No attribute: resetTransform defaults to false, no own transform -> the base's.
  expect_near(d.instances[2].to_world.point({0, 0, 0}), {0, 0, 3});
  EXPECT_EQ(d.instances[2].name, "MeshInstance id=3");
  EXPECT_EQ(d.instances[2].base_mesh, 0);
}

TEST(XmlLoader, InlineMeshesAreCompactedWithOffsetsAndTexcoords) {
  SceneText s;
  s.vertices = R"(
  <VertexData>
    9 9 9
    0 0 0
    1 0 0
    1 1 0
    0 1 0
  </VertexData>
  <TexCoordData>
    0.5 0.5
    0 0
    1 0
    1 1
    0 1
    0.25 0.75
  </TexCoordData>)";
  s.objects = R"(
  <Objects>
    <Mesh id="1" shadingMode="smooth"><Material>1</Material><Faces vertexOffset="1">1 2 3 <!-- a comment inside a value --> 1 3 4</Faces></Mesh>
    <Mesh id="2"><Material>1</Material><Faces vertexOffset="1" textureOffset="2">1 2 3</Faces></Mesh>
    <Triangle id="4"><Material>1</Material><Indices>5 4 2</Indices></Triangle>
    <Sphere id="1"><Material>1</Material><Center>4</Center><Radius>0.5</Radius></Sphere>
  </Objects>)";
  const SceneDesc d = load_text("offsets.xml", s.str());
  ASSERT_EQ(d.meshes.size(), 3u);
  const MeshDesc& m = d.meshes[0];
  EXPECT_EQ(m.name, "Mesh id=1");
  EXPECT_TRUE(m.smooth);
  // Listed 1 2 3 / 1 3 4 (1-based) + vertexOffset 1 -> file vertices 2 3 4 5 -> (0 0 0) (1 0 0) (1 1 0) (0 1 0).
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(m.positions[0], Vec3f(0, 0, 0));
  EXPECT_EQ(m.positions[3], Vec3f(0, 1, 0));
  // uv index = listed + textureOffset (absent: 0), like vertex index = listed + vertexOffset: entries 1..4.
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[0].x, 0.5f);
  EXPECT_EQ(m.uvs[0].y, 0.5f);
  EXPECT_EQ(m.uvs[3].x, 1.0f);
  EXPECT_EQ(m.uvs[3].y, 1.0f);
  // textureOffset 2: listed 1 -> uv entry 3 (1-based) = (1 0); listed 3 -> entry 5 = (0 1).
  const MeshDesc& t = d.meshes[1];
  ASSERT_EQ(t.uvs.size(), 3u);
  EXPECT_EQ(t.uvs[0].x, 1.0f);
  EXPECT_EQ(t.uvs[0].y, 0.0f);
  EXPECT_EQ(t.uvs[2].x, 0.0f);
  EXPECT_EQ(t.uvs[2].y, 1.0f);
  // Triangle: one-triangle mesh, 1-based.
  const MeshDesc& tri = d.meshes[2];
  EXPECT_EQ(tri.name, "Triangle id=4");
  EXPECT_EQ(tri.positions, (std::vector<Vec3f>{{0, 1, 0}, {1, 1, 0}, {0, 0, 0}}));
  EXPECT_EQ(tri.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(d.spheres[0].center, Vec3f(1, 1, 0));
  EXPECT_EQ(d.spheres[0].name, "Sphere id=1");
}

TEST(XmlLoader, ZeroBasedIndexingAppliesToFacesIndicesAndCenters) {
  SceneText s;
  s.top = "\n  <ZeroBasedIndexing>true</ZeroBasedIndexing>";
  s.objects = R"(
  <Objects>
    <Mesh id="1"><Material>1</Material><Faces>0 1 2</Faces></Mesh>
    <Triangle id="1"><Material>1</Material><Indices>1 2 3</Indices></Triangle>
    <Sphere id="1"><Material>1</Material><Center>3</Center><Radius>1</Radius></Sphere>
  </Objects>)";
  const SceneDesc d = load_text("zero_based.xml", s.str());
  EXPECT_EQ(d.meshes[0].positions, (std::vector<Vec3f>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}));
  EXPECT_EQ(d.meshes[1].positions, (std::vector<Vec3f>{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  EXPECT_EQ(d.spheres[0].center, Vec3f(0, 1, 0));
}

TEST(XmlLoader, CameraForms) {
  SceneText s;
  s.cameras = R"(
  <Cameras>
    <Camera id="1">
      <Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
      <NearPlane>-1 1 -0.5 0.5</NearPlane><NearDistance>2</NearDistance>
      <ImageResolution>32 16</ImageResolution><ImageName>plain.png</ImageName>
    </Camera>
    <Camera id="2" type="lookAt" handedness="left">
      <Position>1 2 3</Position><GazePoint>1 2 0</GazePoint><Up>0 1 0</Up><FovY>60</FovY>
      <NearDistance>1</NearDistance><ImageResolution>20 10</ImageResolution><ImageName>look.exr</ImageName>
      <NumSamples>16</NumSamples><FocusDistance>5</FocusDistance><ApertureSize>0.5</ApertureSize>
      <Tonemap><TMO>Photographic</TMO><TMOOptions>0.36 2</TMOOptions><Saturation>0.8</Saturation><Gamma>sRGB</Gamma></Tonemap>
      <Renderer>PathTracing</Renderer><RendererParams>RussianRoulette NextEventEstimation</RendererParams>
    </Camera>
    <Camera id="3" type="simple">
      <Position>0 0 0</Position><Gaze>1 0 0</Gaze><Up>0 0 1</Up><FovY>30</FovY>
      <ImageResolution>8 8</ImageResolution><ImageName>simple.exr</ImageName>
      <Tonemap><TMO>Photographic</TMO><TMOOptions>0.18 1</TMOOptions></Tonemap>
      <GammaCorrection>sRGB</GammaCorrection>
    </Camera>
  </Cameras>)";
  const SceneDesc d = load_text("cameras.xml", s.str());
  ASSERT_EQ(d.cameras.size(), 3u);
  const CameraDesc& a = d.cameras[0];
  EXPECT_EQ(a.id, "1");
  EXPECT_FALSE(a.use_fov);
  EXPECT_EQ(a.near_plane, (std::array<float, 4>{-1, 1, -0.5f, 0.5f}));
  EXPECT_FLOAT_EQ(a.near_distance, 2.0f);
  EXPECT_EQ(a.width, 32);
  EXPECT_EQ(a.height, 16);
  EXPECT_EQ(a.num_samples, 1);
  EXPECT_FALSE(a.tonemap.has_value());
  EXPECT_FALSE(a.renderer_explicit);
  EXPECT_EQ(a.renderer, RendererKind::RayTracing);
  EXPECT_FALSE(a.left_handed);

  const CameraDesc& b = d.cameras[1];
  EXPECT_TRUE(b.use_fov);
  EXPECT_FLOAT_EQ(b.fov_y_deg, 60.0f);
  EXPECT_EQ(b.gaze, Vec3f(0, 0, -3));
  EXPECT_TRUE(b.left_handed);
  EXPECT_EQ(b.num_samples, 16);
  EXPECT_FLOAT_EQ(b.focus_distance, 5.0f);
  EXPECT_FLOAT_EQ(b.aperture_size, 0.5f);
  ASSERT_TRUE(b.tonemap.has_value());
  EXPECT_FLOAT_EQ(b.tonemap->key, 0.36f);
  EXPECT_FLOAT_EQ(b.tonemap->burn_percent, 2.0f);
  EXPECT_FLOAT_EQ(b.tonemap->saturation, 0.8f);
  EXPECT_TRUE(b.tonemap->srgb);
  EXPECT_EQ(b.renderer, RendererKind::PathTracing);
  EXPECT_TRUE(b.pt.russian_roulette && b.pt.next_event_estimation && !b.pt.importance_sampling);

  const CameraDesc& c = d.cameras[2];
  EXPECT_TRUE(c.use_fov);
  EXPECT_FLOAT_EQ(c.near_distance, 1.0f);  // optional for FovY cameras
  ASSERT_TRUE(c.tonemap.has_value());
  EXPECT_TRUE(c.tonemap->srgb);  // 2018 GammaCorrection
  EXPECT_FALSE(c.srgb_without_tonemap);
  EXPECT_TRUE(d.warnings.empty());
}

// MotionBlur on every object kind is a world-space translation over the shutter; BackfaceCulling is read as given;
// 2018 GammaCorrection sRGB without a Tonemap sRGB-encodes the LDR preview.
TEST(XmlLoader, MotionBlurBackfaceCullingAndGammaCorrection) {
  SceneText s;
  s.top = R"(
  <BackfaceCulling>false</BackfaceCulling>)";
  s.cameras = R"(
  <Cameras><Camera id="1"><Position>0 0 10</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
    <NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>4 4</ImageResolution>
    <ImageName>out.png</ImageName><GammaCorrection>sRGB</GammaCorrection></Camera></Cameras>)";
  s.objects = R"(
  <Objects>
    <Mesh id="1"><Material>1</Material><Faces>1 2 3</Faces><MotionBlur>0 0 4</MotionBlur></Mesh>
    <Triangle id="1"><Material>1</Material><Indices>1 2 3</Indices></Triangle>
    <Sphere id="1"><Material>1</Material><Center>1</Center><Radius>1</Radius><MotionBlur>1 -1 0.5</MotionBlur></Sphere>
    <MeshInstance id="2" baseMeshId="1"><MotionBlur>3 0 0</MotionBlur></MeshInstance>
  </Objects>)";
  const SceneDesc d = load_text("motion.xml", s.str());
  ASSERT_EQ(d.meshes.size(), 2u);
  EXPECT_EQ(d.meshes[0].motion, Vec3f(0, 0, 4));
  EXPECT_EQ(d.meshes[1].motion, Vec3f(0.0f));
  EXPECT_EQ(d.spheres[0].motion, Vec3f(1, -1, 0.5f));
  ASSERT_EQ(d.instances.size(), 1u);
  EXPECT_EQ(d.instances[0].motion, Vec3f(3, 0, 0));
  EXPECT_TRUE(d.unsupported.empty());
  EXPECT_EQ(d.backface_culling, std::optional<bool>(false));
  EXPECT_TRUE(d.cameras.back().srgb_without_tonemap);
  EXPECT_FALSE(load_text("plain.xml", SceneText{}.str()).backface_culling.has_value());
}

// 2017: bare <Camera> under <Scene>, `id = "1"` spacing; 2018: Scene-level Integrator/IntegratorParams; CRLF.
TEST(XmlLoader, OlderYearVariants) {
  const std::string xml =
      "<Scene>\r\n"
      "  <Integrator>PathTracing</Integrator>\r\n"
      "  <IntegratorParams>ImportanceSampling</IntegratorParams>\r\n"
      "  <Camera id = \"1\" type = \"simple\">\r\n"
      "    <Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>\r\n"
      "    <ImageResolution>4 4</ImageResolution><ImageName>old.png</ImageName>\r\n"
      "  </Camera>\r\n"
      "  <Materials><Material id = \"1\"><DiffuseReflectance>1 1 1</DiffuseReflectance></Material></Materials>\r\n"
      "  <VertexData>0 0 0</VertexData>\r\n"
      "  <Objects><Sphere id = \"1\"><Material>1</Material><Center>1</Center><Radius>2</Radius></Sphere></Objects>\r\n"
      "</Scene>\r\n";
  const SceneDesc d = load_text("old_years.xml", xml);
  ASSERT_EQ(d.cameras.size(), 1u);
  EXPECT_EQ(d.cameras[0].renderer, RendererKind::PathTracing);
  EXPECT_TRUE(d.cameras[0].pt.importance_sampling);
  EXPECT_FALSE(d.cameras[0].pt.next_event_estimation);
  EXPECT_FLOAT_EQ(d.spheres[0].radius, 2.0f);
  EXPECT_TRUE(d.warnings.empty());
}

TEST(XmlLoader, EveryLightForm) {
  SceneText s;
  s.top = R"(
  <Textures><Images><Image id="3">env/sky.exr</Image></Images></Textures>
  <Lights>
    <AmbientLight>1 2 3</AmbientLight>
    <PointLight id="1"><Position>0 5 0</Position><Intensity>100 100 100</Intensity></PointLight>
    <DirectionalLight id="1"><Direction>1 -0.8 -1</Direction><Radiance>200 200 200</Radiance></DirectionalLight>
    <SpotLight id="1"><Position>0 1 0</Position><Direction>0 -1 0</Direction><Intensity>5 5 5</Intensity>
      <CoverageAngle>40</CoverageAngle><FalloffAngle>30</FalloffAngle></SpotLight>
    <AreaLight id="1"><Position>0 9 0</Position><Normal>0 -2 0</Normal><Size>3</Size><Radiance>7 7 7</Radiance></AreaLight>
    <AreaLight id="2"><Position>0 9 0</Position><Normal>0 -1 0</Normal><Size>2</Size><Intensity>150000 150000 150000</Intensity></AreaLight>
    <AreaLight id="3"><Position>1 2 3</Position><EdgeVector1>2 0 0</EdgeVector1><EdgeVector2>0 0 1</EdgeVector2>
      <Intensity>9 9 9</Intensity></AreaLight>
    <SphericalDirectionalLight id="1"><EnvMapName>textures/pisa.exr</EnvMapName></SphericalDirectionalLight>
    <SphericalDirectionalLight id="2"><ImageId>3</ImageId></SphericalDirectionalLight>
  </Lights>)";
  s.objects = R"(
  <Objects>
    <LightMesh id="1"><Material>1</Material><Radiance>1.21 1.21 1.21</Radiance><Faces>1 2 3</Faces></LightMesh>
    <LightSphere id="1"><Material>1</Material><Center>2</Center><Radius>0.2</Radius><Radiance>31.8 31.8 31.8</Radiance></LightSphere>
    <LightSphere id="2"><Center>2</Center><Radius>0.3</Radius><Radiance>1 1 1</Radiance></LightSphere>
  </Objects>)";
  const std::string path = write_tmp("lights/lights.xml", s.str());
  write_tmp("lights/textures/pisa.exr", "an environment map must exist; it is read when the world is built");
  write_tmp("lights/env/sky.exr", "-");
  const SceneDesc d = load_ceng795_xml(path);
  EXPECT_EQ(d.ambient_light, Rgb(1, 2, 3));
  ASSERT_EQ(d.point_lights.size(), 1u);
  EXPECT_EQ(d.point_lights[0].position, Vec3f(0, 5, 0));
  ASSERT_EQ(d.directional_lights.size(), 1u);
  EXPECT_EQ(d.directional_lights[0].radiance, Rgb(200.0f));
  ASSERT_EQ(d.spot_lights.size(), 1u);
  EXPECT_FLOAT_EQ(d.spot_lights[0].coverage_deg, 40.0f);
  EXPECT_FLOAT_EQ(d.spot_lights[0].falloff_deg, 30.0f);
  ASSERT_EQ(d.area_lights.size(), 3u);
  EXPECT_EQ(d.area_lights[0].normal, Vec3f(0, -1, 0));
  EXPECT_FALSE(d.area_lights[0].radiance_is_intensity);
  EXPECT_TRUE(d.area_lights[1].radiance_is_intensity);
  ASSERT_TRUE(d.area_lights[2].edges.has_value());
  EXPECT_EQ((*d.area_lights[2].edges)[0], Vec3f(2, 0, 0));
  EXPECT_EQ(d.area_lights[2].normal, Vec3f(0, -1, 0));  // normalize(e1 x e2)
  ASSERT_EQ(d.env_lights.size(), 2u);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  EXPECT_EQ(d.env_lights[0].image_path, dir + "/textures/pisa.exr");
  EXPECT_EQ(d.env_lights[1].image_path, dir + "/env/sky.exr");
  EXPECT_NE(d.env_lights[0].element.find("SphericalDirectionalLight id=1"), std::string::npos);
  EXPECT_TRUE(d.unsupported.empty());  // environment lights are rendered
  ASSERT_EQ(d.meshes.size(), 1u);
  EXPECT_EQ(d.meshes[0].name, "LightMesh id=1");
  EXPECT_EQ(d.meshes[0].emission, std::optional<Rgb>(Rgb(1.21f)));
  ASSERT_EQ(d.spheres.size(), 2u);
  EXPECT_EQ(d.spheres[0].emission, std::optional<Rgb>(Rgb(31.8f)));
  EXPECT_EQ(d.spheres[0].center, Vec3f(1, 0, 0));
  EXPECT_EQ(d.spheres[1].material, -1);  // a light object without a material only emits
}

TEST(XmlLoader, MaterialsAndBrdfsMapIdsToIndices) {
  SceneText s;
  s.top = R"(
  <BRDFs>
    <TorranceSparrow id="5" kdfresnel="true"><Exponent>50</Exponent><RefractiveIndex>0.37</RefractiveIndex></TorranceSparrow>
    <OriginalPhong id="1"><Exponent>10</Exponent></OriginalPhong>
    <ModifiedPhong id="2" normalized="true"><Exponent>20</Exponent></ModifiedPhong>
    <OriginalBlinnPhong id="3"><Exponent>30</Exponent></OriginalBlinnPhong>
    <ModifiedBlinnPhong id="4" normalized="false"><Exponent>40</Exponent></ModifiedBlinnPhong>
  </BRDFs>)";
  s.materials = R"(
  <Materials>
    <Material id="4" BRDF="3" degamma="true">
      <AmbientReflectance>0.1 0.1 0.1</AmbientReflectance>
      <DiffuseReflectance>0.5 0.4 0.3</DiffuseReflectance>
      <SpecularReflectance>1 1 1</SpecularReflectance>-->
      <PhongExponent>7</PhongExponent>
    </Material>
    <Material id="1" type="conductor">
      <MirrorReflectance>1 0.86 0.57</MirrorReflectance>
      <RefractionIndex>0.370</RefractionIndex>
      <AbsorptionIndex>2.820</AbsorptionIndex>
      <Roughness>0.1</Roughness>
    </Material>
    <Material id="2" type="dielectric">
      <AbsorptionCoefficient>0.01 0.02 0.03</AbsorptionCoefficient>
      <RefractionIndex>1.55</RefractionIndex>
    </Material>
    <Material id="3" type="mirror"><MirrorReflectance>1 1 1</MirrorReflectance></Material>
    <Material id="9"><Transparency>0.98 0.98 0.98</Transparency><RefractionIndex>1.5</RefractionIndex></Material>
  </Materials>)";
  s.objects = R"(
  <Objects>
    <Mesh id="1"><Material>9</Material><Faces>1 2 3</Faces></Mesh>
    <Sphere id="1"><Material>4</Material><Center>1</Center><Radius>1</Radius></Sphere>
  </Objects>)";
  const SceneDesc d = load_text("materials.xml", s.str());
  ASSERT_EQ(d.brdfs.size(), 5u);
  EXPECT_EQ(d.brdfs[0].kind, BrdfKind::TorranceSparrow);
  EXPECT_TRUE(d.brdfs[0].kd_fresnel);
  EXPECT_FLOAT_EQ(*d.brdfs[0].refractive_index, 0.37f);
  EXPECT_EQ(d.brdfs[1].kind, BrdfKind::OriginalPhong);
  EXPECT_EQ(d.brdfs[2].kind, BrdfKind::ModifiedPhong);
  EXPECT_TRUE(d.brdfs[2].normalized);
  EXPECT_EQ(d.brdfs[3].kind, BrdfKind::OriginalBlinnPhong);
  EXPECT_EQ(d.brdfs[4].kind, BrdfKind::ModifiedBlinnPhong);
  EXPECT_FALSE(d.brdfs[4].normalized);
  EXPECT_FLOAT_EQ(d.brdfs[4].exponent, 40.0f);

  ASSERT_EQ(d.materials.size(), 5u);
  const MaterialDesc& m0 = d.materials[0];
  EXPECT_EQ(m0.id, 4);
  EXPECT_EQ(m0.brdf, std::optional<int>(3));  // BRDF id 3 is the 4th BRDF
  EXPECT_EQ(d.brdfs[size_t(*m0.brdf)].id, 3);
  EXPECT_TRUE(m0.degamma);
  EXPECT_EQ(m0.diffuse, Rgb(0.5f, 0.4f, 0.3f));
  EXPECT_EQ(m0.specular, Rgb(1.0f));  // the stray "-->" after it is ignored
  EXPECT_FLOAT_EQ(m0.phong_exponent, 7.0f);
  EXPECT_EQ(m0.type, MaterialType::Plain);
  const MaterialDesc& m1 = d.materials[1];
  EXPECT_EQ(m1.type, MaterialType::Conductor);
  EXPECT_FALSE(m1.brdf.has_value());
  EXPECT_FLOAT_EQ(m1.refraction_index, 0.37f);
  EXPECT_TRUE(m1.has_refraction_index);
  EXPECT_FLOAT_EQ(m1.absorption_index, 2.82f);
  EXPECT_FLOAT_EQ(m1.roughness, 0.1f);
  EXPECT_EQ(d.materials[2].type, MaterialType::Dielectric);
  EXPECT_EQ(d.materials[2].absorption_coefficient, Rgb(0.01f, 0.02f, 0.03f));
  EXPECT_EQ(d.materials[3].type, MaterialType::Mirror);
  EXPECT_EQ(d.materials[4].type, MaterialType::Plain);  // 2019 Transparency marker is build_material's to read
  EXPECT_EQ(d.materials[4].transparency, Rgb(0.98f));
  EXPECT_FALSE(d.materials[2].has_refraction_index && d.materials[0].has_refraction_index);
  EXPECT_EQ(d.meshes[0].material, 4);
  EXPECT_EQ(d.spheres[0].material, 0);
  EXPECT_TRUE(d.warnings.empty());
}

TEST(XmlLoader, GlobalsAndDefaults) {
  SceneText s;
  s.top = R"(
  <ShadowRayEpsilon>1e-3</ShadowRayEpsilon>
  <IntersectionTestEpsilon>1e-6</IntersectionTestEpsilon>
  <MaxRecursionDepth> 6 </MaxRecursionDepth>)";
  s.cameras = std::string(xml_test::kCamera) + "\n  <BackgroundColor_typo>1</BackgroundColor_typo>";
  const std::string path = write_tmp("globals.xml", s.str());
  const SceneDesc d = load_ceng795_xml(path);
  EXPECT_EQ(d.source_path, path);
  EXPECT_EQ(d.format, "ceng795-xml");
  EXPECT_FLOAT_EQ(*d.shadow_ray_epsilon, 1e-3f);
  EXPECT_FLOAT_EQ(*d.intersection_test_epsilon, 1e-6f);
  EXPECT_EQ(d.max_recursion_depth, std::optional<int>(6));
  EXPECT_EQ(d.ambient_light, Rgb(0.0f));
  EXPECT_TRUE(d.unsupported.empty());
  ASSERT_EQ(d.warnings.size(), 1u);  // the unknown element is reported with its line, not dropped silently
  EXPECT_NE(d.warnings[0].find("line 17 (BackgroundColor_typo): unknown element <BackgroundColor_typo> ignored"),
            std::string::npos)
      << d.warnings[0];

  const SceneDesc e = load_text("no_globals.xml", SceneText{}.str());
  EXPECT_FALSE(e.shadow_ray_epsilon.has_value());
  EXPECT_FALSE(e.max_recursion_depth.has_value());
}

// Kiln's own filtered Interpolation values, trilinear and ewa, are read in both texture forms.
TEST(XmlLoader, FilteredInterpolationInBothTextureForms) {
  SceneText s;
  s.top = R"(
  <Textures>
    <Texture id="1"><ImageName>textures/a.jpg</ImageName><Interpolation>trilinear</Interpolation></Texture>
    <Texture id="2"><ImageName>textures/a.jpg</ImageName><Interpolation>ewa</Interpolation></Texture>
    <Images><Image id="1">textures/b.png</Image></Images>
    <TextureMap id="3" type="image"><ImageId>1</ImageId><Interpolation>ewa</Interpolation></TextureMap>
    <TextureMap id="4" type="image"><ImageId>1</ImageId><Interpolation>trilinear</Interpolation></TextureMap>
  </Textures>)";
  const SceneDesc d = load_text("filtered_interpolation.xml", s.str());
  EXPECT_TRUE(d.warnings.empty());
  ASSERT_EQ(d.textures.size(), 4u);
  EXPECT_EQ(d.textures[0].filter, TextureFilter::Trilinear);
  EXPECT_EQ(d.textures[1].filter, TextureFilter::Ewa);
  EXPECT_EQ(d.textures[2].filter, TextureFilter::Ewa);
  EXPECT_EQ(d.textures[3].filter, TextureFilter::Trilinear);
}

// Textures of the 2019 form, with a BackgroundTexture, load with nothing left unsupported.
TEST(XmlLoader, TexturesAndBackgroundTextureAreRead) {
  SceneText s;
  s.top = R"(
  <BackgroundTexture>textures/galaxy.jpg</BackgroundTexture>
  <Textures>
    <Texture id="1" bumpmap="true" bumpmapMultiplier="3"><ImageName>textures/a.jpg</ImageName>
      <Interpolation>bilinear</Interpolation><DecalMode>replace_kd</DecalMode><Normalizer>255</Normalizer></Texture>
    <Texture id="2"><ImageName>checkerboard</ImageName><BlackColor>0 0 0</BlackColor></Texture>
    <Texture id="3"><ImageName>perlin</ImageName><Appearance>vein</Appearance></Texture>
  </Textures>)";
  s.objects = R"(
  <Objects>
    <Mesh id="1"><Material>1</Material><Texture>1</Texture><Faces>1 2 3</Faces></Mesh>
    <Sphere id="1"><Material>1</Material><Texture>2</Texture><Center>1</Center><Radius>1</Radius></Sphere>
    <Sphere id="2"><Material>1</Material><Textures>2 3</Textures><Center>1</Center><Radius>1</Radius></Sphere>
  </Objects>)";
  const SceneDesc d = load_text("unsupported.xml", s.str());
  EXPECT_TRUE(d.unsupported.empty());
  // Textures are read: the background image first, then the three <Texture> elements.
  ASSERT_EQ(d.textures.size(), 4u);
  EXPECT_EQ(d.background_texture, std::optional<int>(0));
  // The 2019 background has no Interpolation nor Normalizer: the texel under the pixel centre, at the file's values.
  EXPECT_EQ(d.textures[0].decal, DecalMode::ReplaceBackground);
  EXPECT_EQ(d.textures[0].filter, TextureFilter::Nearest);
  EXPECT_EQ(d.textures[0].normalizer, std::optional<float>(1.0f));
  EXPECT_TRUE(d.textures[1].bump);
  EXPECT_FLOAT_EQ(d.textures[1].bump_factor, 3.0f);
  EXPECT_FLOAT_EQ(*d.textures[1].normalizer, 255.0f);
  EXPECT_EQ(d.textures[2].source, TextureSource::Checkerboard);
  EXPECT_EQ(d.textures[3].noise, NoiseConversion::AbsVal);
  EXPECT_EQ(d.meshes[0].textures, std::vector<int>{1});
  EXPECT_EQ(d.spheres[1].textures, (std::vector<int>{2, 3}));
  EXPECT_EQ(d.meshes.size(), 1u);
  EXPECT_EQ(d.spheres.size(), 2u);
}

// VertexData / TexCoordData / Faces binaryFile (little-endian int32 count + data) and plyFile, relative to the XML.
TEST(XmlLoader, BinaryFilesAndPlyFilesRelativeToTheXml) {
  auto le32 = [](std::string& s, uint32_t v) {
    for (int i = 0; i < 4; ++i) s.push_back(char((v >> (8 * i)) & 0xff));
  };
  auto lef = [&](std::string& s, float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    le32(s, u);
  };
  std::string verts, uvs, faces;
  le32(verts, 4);
  for (float f : {0.f, 0.f, 0.f, 2.f, 0.f, 0.f, 2.f, 2.f, 0.f, 0.f, 2.f, 0.f}) lef(verts, f);
  le32(uvs, 4);
  for (float f : {0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 1.f}) lef(uvs, f);
  le32(faces, 2);
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) le32(faces, i);
  write_tmp("binary/geometry/v.bin", verts);
  write_tmp("binary/geometry/uv.bin", uvs);
  write_tmp("binary/geometry/f.bin", faces);
  write_tmp("binary/ply/tri.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  SceneText s;
  s.top = "\n  <ZeroBasedIndexing>true</ZeroBasedIndexing>";
  s.vertices = R"(
  <VertexData binaryFile="geometry/v.bin"/>
  <TexCoordData binaryFile="geometry/uv.bin"></TexCoordData>)";
  s.objects = R"(
  <Objects>
    <Mesh id="1"><Material>1</Material><Faces binaryFile="geometry/f.bin"/></Mesh>
    <Mesh id="2"><Material>1</Material><Faces plyFile="ply/tri.ply"/></Mesh>
  </Objects>)";
  const SceneDesc d = load_ceng795_xml(write_tmp("binary/scene.xml", s.str()));
  ASSERT_EQ(d.meshes.size(), 2u);
  EXPECT_EQ(d.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(d.meshes[0].positions[2], Vec3f(2, 2, 0));
  ASSERT_EQ(d.meshes[0].uvs.size(), 4u);
  EXPECT_EQ(d.meshes[0].uvs[2].x, 1.0f);
  EXPECT_EQ(d.meshes[1].name, "Mesh id=2");
  EXPECT_EQ(d.meshes[1].positions.size(), 3u);
  EXPECT_EQ(d.meshes[1].indices, (std::vector<uint32_t>{0, 1, 2}));
}

}  // namespace
}  // namespace kiln
