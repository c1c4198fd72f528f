#include "renderer/world/emission_images.h"

#include "core/error.h"
#include "renderer/image_io/image_io.h"

namespace kiln {

std::shared_ptr<const EmissionImage> EmissionImages::get(const EmissionImageDesc& desc, Rgb scale) {
  const auto key = std::make_tuple(desc.path, scale.r, scale.g, scale.b);
  if (const auto it = built_.find(key); it != built_.end()) return it->second;
  try {
    auto read = read_.find(desc.path);
    if (read == read_.end()) {
      Image img = read_image(desc.path);
      if (!is_float_image_format(desc.path))
        for (Rgb& c : img.pixels())
          for (int i = 0; i < 3; ++i) c[i] = srgb_to_linear(c[i]);
      read = read_.emplace(desc.path, std::move(img)).first;
    }
    auto image = std::make_shared<const EmissionImage>(read->second, scale);
    built_.emplace(key, image);
    return image;
  } catch (const Error& e) {
    throw Error(scene_.source_path, desc.element, "area light image '" + desc.path + "': " + e.what());
  }
}

std::vector<std::array<Vec2f, 3>> triangle_uvs(std::span<const uint32_t> indices, std::span<const Vec2f> uvs) {
  std::vector<std::array<Vec2f, 3>> out(indices.size() / 3, {Vec2f(0, 0), Vec2f(1, 0), Vec2f(1, 1)});
  if (uvs.empty()) return out;
  for (size_t i = 0; i < out.size(); ++i)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = indices[3 * i + k];
      out[i][k] = v < uvs.size() ? uvs[v] : Vec2f(0.0f, 0.0f);
    }
  return out;
}

}  // namespace kiln
