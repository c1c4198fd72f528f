// The emission images of a scene's area lights (MeshDesc / QuadricDesc::emission_image), read while the world is
// built: each file once (EXR directly, other formats through the OpenImageIO plugin; 8- and 16-bit formats
// sRGB-decoded, as pbrt-v4 decodes them), one EmissionImage per file and multiplier, shared by its shapes.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "core/image.h"
#include "lights/emission_image.h"
#include "scenes/scene.h"

namespace kiln {

class EmissionImages {
 public:
  explicit EmissionImages(const SceneDesc& scene) : scene_(scene) {}
  // The image of `desc` times `scale`. Throws kiln::Error naming the scene file and the element when the image
  // cannot be read, is empty or holds values that are not finite.
  std::shared_ptr<const EmissionImage> get(const EmissionImageDesc& desc, Rgb scale);

 private:
  const SceneDesc& scene_;
  std::map<std::string, Image> read_;
  std::map<std::tuple<std::string, float, float, float>, std::shared_ptr<const EmissionImage>> built_;
};

// Each triangle's corners' (u, v): from the per-vertex uvs, or pbrt's (0,0), (1,0), (1,1) when the mesh has none.
std::vector<std::array<Vec2f, 3>> triangle_uvs(std::span<const uint32_t> indices, std::span<const Vec2f> uvs);

}  // namespace kiln
