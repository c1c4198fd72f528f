// Helpers for the CENG795 XML loader tests: scratch files and a minimal valid scene to vary.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace kiln::xml_test {

inline std::filesystem::path tmp_dir() {
  const std::filesystem::path dir = std::filesystem::path(KILN_TEST_TMP) / "xml";
  std::filesystem::create_directories(dir);
  return dir;
}

// Writes bytes to KILN_TEST_TMP/xml/<name> (subdirectories created) and returns the path.
inline std::string write_tmp(const std::string& name, const std::string& bytes) {
  const std::filesystem::path p = tmp_dir() / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  EXPECT_TRUE(out.good()) << p;
  return p.string();
}

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no kiln::Error thrown";
  return {};
}

inline const char* const kCamera = R"(
  <Cameras>
    <Camera id="1">
      <Position>0 0 10</Position>
      <Gaze>0 0 -1</Gaze>
      <Up>0 1 0</Up>
      <NearPlane>-1 1 -1 1</NearPlane>
      <NearDistance>1</NearDistance>
      <ImageResolution>16 8</ImageResolution>
      <ImageName>out.png</ImageName>
    </Camera>
  </Cameras>)";

inline const char* const kMaterial = R"(
  <Materials>
    <Material id="1">
      <DiffuseReflectance>1 1 1</DiffuseReflectance>
    </Material>
  </Materials>)";

inline const char* const kVertices = R"(
  <VertexData>
    0 0 0
    1 0 0
    1 1 0
    0 1 0
  </VertexData>)";

inline const char* const kOneMesh = R"(
  <Objects>
    <Mesh id="1">
      <Material>1</Material>
      <Faces>1 2 3</Faces>
    </Mesh>
  </Objects>)";

// A small valid scene; each part can be replaced.
struct SceneText {
  std::string top;  // extra top-level elements
  std::string cameras = kCamera;
  std::string materials = kMaterial;
  std::string vertices = kVertices;
  std::string objects = kOneMesh;
  std::string str() const {
    return "<Scene>\n  <BackgroundColor>0 0 0</BackgroundColor>" + top + cameras + materials + vertices + objects +
           "\n</Scene>\n";
  }
};

}  // namespace kiln::xml_test
