// LDR previews: the course's Photographic operator (Reinhard et al. 2002, spec §10), the course's LDR convention
// (radiance already in 0-255, clamped, no gamma) and a plain clamp + gamma.
#pragma once
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "scenes/scene.h"

namespace kiln {

enum class PreviewKind { Photographic, CourseLdr, ClampGamma };

struct PreviewSettings {
  PreviewKind kind = PreviewKind::ClampGamma;
  TonemapDesc tonemap;  // Photographic parameters and gamma
  float gamma = 2.2f;   // ClampGamma
  bool srgb = true;     // ClampGamma: sRGB curve instead of the power gamma
  bool course_ldr_srgb = false;  // CourseLdr: the 0-255 value through the sRGB curve (2018 GammaCorrection sRGB)
};

// How a camera's image becomes a PNG: its Tonemap if any; a .png ImageName without Tonemap is the course LDR
// convention; otherwise clamp to [0,1] and encode (CS171: gamma 2.2, else sRGB).
PreviewSettings preview_for_camera(const CameraDesc& camera, const SceneDesc& scene);
std::vector<uint8_t> to_ldr(const Image& img, const PreviewSettings& settings);
// The sRGB transfer curve (IEC 61966-2-1) of a linear value in [0, 1].
float srgb_encode(float linear);

}  // namespace kiln
