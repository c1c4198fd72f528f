// The radiance of an area light that emits an image (pbrt-v4's "diffuse" area light with "filename"): the light's
// radiance at a surface point of parameters (u, v) is the image at (u, 1 - v) (v = 0 is the image's bottom row, as
// for pbrt's image textures), interpolated bilinearly between texel centres with the edges clamped, negative values
// read as 0. The texels hold pbrt's "scale" already (each channel times scale's). Shared by every shape that one AreaLightSource lights.
#pragma once
#include <memory>

#include "core/image.h"
#include "core/vec.h"

namespace kiln {

class EmissionImage {
 public:
  // Throws kiln::Error when the image is empty or holds a value that is not finite.
  EmissionImage(Image texels, Rgb scale);

  Rgb radiance(Vec2f uv) const;
  // The mean over the texels: the mean radiance over (u, v) (what the light sampler's power takes).
  Rgb mean() const { return mean_; }
  int width() const { return texels_.width(); }
  int height() const { return texels_.height(); }

 private:
  Image texels_;
  Rgb mean_;
};

}  // namespace kiln
