// Background textures (CENG795 spec §1 BackgroundTexture, §8 replace_background): camera rays that miss every
// surface see the texel under their pixel's centre, u = (x + 1/2) / width, v = (y + 1/2) / height with y from the
// top, in every integrator; pixels the object covers do not change. Scenes are written as XML in both spellings
// (2019 <BackgroundTexture>, 2021 replace_background TextureMap) and rendered in-process.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"
#include "scenes/material_mapping.h"

namespace kiln::test {
namespace {

// The output is 32 x 24; the background 48 x 36, 1.5 texels per pixel, so pixel x shows texel floor(1.5 x + 0.75):
// the pixel centre's texel, which neither a corner (floor(1.5 x)) nor a flipped v would give.
constexpr int kWidth = 32, kHeight = 24, kTexWidth = 48, kTexHeight = 36;
constexpr float kMarker = 1000.0f;  // a BackgroundColor no surface here reaches: tells which pixels saw a miss
constexpr uint32_t kSpp = 4;

// Texel (x, y), y = 0 the top row: every texel its own value.
Rgb texel(int x, int y) { return Rgb(1.0f + float(x), 1.0f + float(y), 0.5f); }

// Element2019Png: the 2019 element with an 8-bit PNG of the same texels (byte values 2x, 3y, 128).
enum class Background { None, Element2019, Element2019Png, TextureMap2021 };
// A diffuse sphere in the middle of the frame, or a mirror sphere filling it (every camera ray hits it, every
// reflected ray leaves the scene).
enum class Object { DiffuseSphere, MirrorAround };

// The object under a point light, seen by a 32 x 24 camera; `renderer` "" is the course ray tracer, "PathTracing"
// the course path tracer.
std::string scene_xml(Background bg, float background_colour, const std::string& renderer, Object object) {
  std::string top;
  if (bg == Background::Element2019) top = "  <BackgroundTexture>textures/background.exr</BackgroundTexture>\n";
  if (bg == Background::Element2019Png) top = "  <BackgroundTexture>textures/background.png</BackgroundTexture>\n";
  if (bg == Background::TextureMap2021)
    top = R"(  <Textures><Images><Image id="1">textures/background.exr</Image></Images>
    <TextureMap id="1" type="image" degamma="true"><ImageId>1</ImageId><Interpolation>nearest</Interpolation>
      <DecalMode>replace_background</DecalMode><Normalizer>2</Normalizer></TextureMap></Textures>
)";
  const std::string bc = std::to_string(background_colour);
  const std::string render_with =
      renderer.empty() ? ""
                       : "<Renderer>" + renderer + "</Renderer><RendererParams>NextEventEstimation</RendererParams>";
  const std::string sphere = object == Object::DiffuseSphere
                                 ? "<Material>1</Material><Center>1</Center><Radius>1.2</Radius>"
                                 : "<Material>2</Material><Center>1</Center><Radius>2.8</Radius>";
  return "<Scene>\n  <BackgroundColor>" + bc + " " + bc + " " + bc + "</BackgroundColor>\n" + top +
         R"(  <MaxRecursionDepth>2</MaxRecursionDepth>
  <Cameras><Camera id="1"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
    <NearPlane>-1 1 -0.75 0.75</NearPlane><NearDistance>1</NearDistance><ImageResolution>32 24</ImageResolution>
    <NumSamples>4</NumSamples><ImageName>bg.exr</ImageName>)" +
         render_with + R"(</Camera></Cameras>
  <Lights><AmbientLight>5 5 5</AmbientLight><PointLight id="1"><Position>1 2 0</Position>
    <Intensity>100 100 100</Intensity></PointLight></Lights>
  <Materials><Material id="1"><AmbientReflectance>1 1 1</AmbientReflectance>
    <DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance>
    <PhongExponent>1</PhongExponent></Material>
    <Material id="2" type="mirror"><MirrorReflectance>0.5 0.5 0.5</MirrorReflectance></Material></Materials>
  <VertexData>0.3 -0.2 -3</VertexData>
  <Objects><Sphere id="1">)" + sphere + R"(</Sphere></Objects>
</Scene>
)";
}

// Writes the background image and the scene; returns the scene's path.
std::string write_scene(const std::string& name, Background bg, float background_colour, const std::string& renderer,
                        Object object) {
  const std::string dir = tmp_dir("background_texture");
  std::filesystem::create_directories(dir + "/textures");
  Image img(kTexWidth, kTexHeight);
  for (int y = 0; y < kTexHeight; ++y)
    for (int x = 0; x < kTexWidth; ++x) img.at(x, y) = texel(x, y);
  write_exr(dir + "/textures/background.exr", img, {}, {});
  std::vector<uint8_t> bytes;
  for (int y = 0; y < kTexHeight; ++y)
    for (int x = 0; x < kTexWidth; ++x) bytes.insert(bytes.end(), {uint8_t(2 * x), uint8_t(3 * y), 128});
  write_png(dir + "/textures/background.png", bytes, kTexWidth, kTexHeight);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << scene_xml(bg, background_colour, renderer, object);
  return path;
}

// The texel pixel (x, y) shows: the one under its centre.
Rgb expected_texel(int x, int y) {
  const double u = (x + 0.5) / kWidth, v = (y + 0.5) / kHeight;
  return texel(int(std::floor(u * kTexWidth)), int(std::floor(v * kTexHeight)));
}

struct Case {
  const char* name;
  SceneRules rules;
  const char* renderer;
};
const Case kCases[] = {{"kiln path tracer", SceneRules::Kiln, "PathTracing"},
                       {"course path tracer", SceneRules::Ceng795Course, "PathTracing"},
                       {"course ray tracer", SceneRules::Ceng795Course, ""}};

// The scene with background `bg` and BackgroundColor `colour`, written as `name` and rendered under case c.
Image render_variant(const std::string& name, Background bg, float colour, const Case& c,
                     Object object = Object::DiffuseSphere) {
  SceneDesc s = load_scene(write_scene(name, bg, colour, c.renderer, object));
  s.rules = c.rules;
  EXPECT_TRUE(s.unsupported.empty()) << name;
  const auto w = build_scene_world(s);
  return render_image(*w, s.cameras[0], scene_settings(s.cameras[0], s, w->features), kSpp, 5);
}

// Renders the scene with the background `bg` and without (BackgroundColor 0, and the marker colour) under every
// integrator. Pixels every sample of which missed (the marker render is the marker there) must be value(texel)
// exactly; pixels no sample of which missed (both plain renders agree) must equal the plain render bit for bit.
template <typename Value>
void expect_background(Background bg, const char* tag, Value value) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(std::string(tag) + ", " + c.name);
    const std::string t(tag);
    const Image plain = render_variant(t + "_plain.xml", Background::None, 0, c);
    const Image marked = render_variant(t + "_marked.xml", Background::None, kMarker, c);
    const Image textured = render_variant(t + "_bg.xml", bg, 0, c);
    int background = 0, covered = 0, wrong_background = 0, wrong_covered = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const Rgb got = textured.at(x, y);
        if (marked.at(x, y) == Rgb(kMarker)) {
          ++background;
          const Rgb want = value(expected_texel(x, y));
          if (!(got == want) && ++wrong_background <= 3)
            ADD_FAILURE() << "background pixel " << x << "," << y << ": got " << got.r << " " << got.g << " " << got.b
                          << ", texel " << want.r << " " << want.g << " " << want.b;
        } else if (marked.at(x, y) == plain.at(x, y)) {
          ++covered;
          if (!(got == plain.at(x, y)) && ++wrong_covered <= 3)
            ADD_FAILURE() << "covered pixel " << x << "," << y << " changed: " << got.r << " vs " << plain.at(x, y).r;
        }
      }
    EXPECT_EQ(wrong_background, 0);
    EXPECT_EQ(wrong_covered, 0);
    // Both kinds must be there in number, or the test would pass on an empty frame or an empty background.
    EXPECT_GT(background, kWidth * kHeight / 2);
    EXPECT_GT(covered, 60);
  }
}

// 2019: no Normalizer (the file's values) and no Interpolation (the texel under the pixel centre).
TEST(BackgroundTexture, Element2019ShowsTheTexelUnderEachPixelCentre) {
  expect_background(Background::Element2019, "bg2019", [](Rgb t) { return t; });
}

// 2021: the TextureMap's Normalizer and degamma apply as for every image texture.
TEST(BackgroundTexture, TextureMap2021ShowsTheNormalisedDegammadTexel) {
  expect_background(Background::TextureMap2021, "bg2021", [](Rgb t) { return pow(t / 2.0f, kDegammaExponent); });
}

// An 8-bit image: the file's values (0-255, the scale of BackgroundColor in the course's LDR scenes), not [0, 1].
// (OpenImageIO returns byte / 255, which Kiln scales back: equal to a few ulps, not bit for bit.)
TEST(BackgroundTexture, Element2019ReadsAnEightBitImageAtItsFileValues) {
  const Image img = render_variant("bg2019_png.xml", Background::Element2019Png, 0, kCases[2]);
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{kWidth - 1, 0}, std::pair{kWidth - 1, kHeight - 1}}) {
    const Rgb t = expected_texel(x, y);  // texel (tx, ty) holds 1 + tx, 1 + ty
    const Rgb want(2.0f * (t.r - 1.0f), 3.0f * (t.g - 1.0f), 128.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y)[c], want[c], 1e-3f) << x << "," << y << " channel " << c;
  }
}

// Only camera rays see the texture: with a mirror filling the frame no camera ray misses, and the reflected rays that
// leave see what they saw without it (the course ray tracer: BackgroundColor; the path tracers: nothing).
TEST(BackgroundTexture, ReflectedRaysStillSeeTheBackgroundColour) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    const Image plain = render_variant("mirror_plain.xml", Background::None, 8, c, Object::MirrorAround);
    const Image textured = render_variant("mirror_bg.xml", Background::Element2019, 8, c, Object::MirrorAround);
    size_t differ = 0;
    for (size_t i = 0; i < plain.pixels().size(); ++i) differ += plain.pixels()[i] == textured.pixels()[i] ? 0 : 1;
    EXPECT_EQ(differ, 0u);
    // The course ray tracer's mirror shows the background colour (half of it) in every pixel.
    if (std::string(c.renderer).empty()) {
      EXPECT_EQ(plain.at(kWidth / 2, kHeight / 2), Rgb(4.0f));
    }
  }
}

}  // namespace
}  // namespace kiln::test
