#include "renderer/film/tonemap.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace kiln {
namespace {

// Offset inside the log-average so that black pixels do not send it to zero (Reinhard 2002's delta).
constexpr double kLogAverageDelta = 1e-5;

uint8_t quantize(float v01) { return uint8_t(std::clamp(std::lround(std::clamp(v01, 0.0f, 1.0f) * 255.0f), 0L, 255L)); }

std::vector<uint8_t> photographic(const Image& img, const TonemapDesc& tm) {
  const auto& px = img.pixels();
  std::vector<float> lum(px.size());
  double log_sum = 0.0;
  for (size_t i = 0; i < px.size(); ++i) {
    lum[i] = std::max(0.0f, px[i].luminance());
    log_sum += std::log(kLogAverageDelta + lum[i]);
  }
  const double log_avg = px.empty() ? 1.0 : std::exp(log_sum / double(px.size()));
  const float scale = float(tm.key / log_avg);
  // White point: the scaled luminance above which burn_percent of the pixels lie (the maximum for 0).
  std::vector<float> sorted(lum);
  float y_white = 0.0f;
  if (!sorted.empty()) {
    const double q = std::clamp(1.0 - tm.burn_percent / 100.0, 0.0, 1.0);
    const size_t k = std::min(sorted.size() - 1, size_t(q * double(sorted.size() - 1) + 0.5));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    y_white = sorted[k] * scale;
  }
  std::vector<uint8_t> out(px.size() * 3);
  for (size_t i = 0; i < px.size(); ++i) {
    const float y = lum[i] * scale;
    float yd = y_white > 0.0f ? y * (1.0f + y / (y_white * y_white)) / (1.0f + y) : y / (1.0f + y);
    for (int c = 0; c < 3; ++c) {
      float v = lum[i] > 0.0f ? yd * std::pow(std::max(0.0f, px[i][c]) / lum[i], tm.saturation) : 0.0f;
      v = std::clamp(v, 0.0f, 1.0f);
      v = tm.srgb ? srgb_encode(v) : std::pow(v, 1.0f / tm.gamma);
      out[i * 3 + size_t(c)] = quantize(v);
    }
  }
  return out;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                                                 [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

}  // namespace

float srgb_encode(float c) { return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

PreviewSettings preview_for_camera(const CameraDesc& camera, const SceneDesc& scene) {
  PreviewSettings p;
  if (camera.tonemap) {
    p.kind = PreviewKind::Photographic;
    p.tonemap = *camera.tonemap;
  } else if (scene.png_gamma_encode) {
    p.kind = PreviewKind::ClampGamma;
    p.srgb = false;
    p.gamma = 2.2f;
  } else if (ends_with(camera.image_name, ".png") || ends_with(camera.image_name, ".ppm")) {
    p.kind = PreviewKind::CourseLdr;
    p.course_ldr_srgb = camera.srgb_without_tonemap;
  } else if (camera.srgb_without_tonemap) {
    p.kind = PreviewKind::ClampGamma;  // an .exr name: clamp to [0, 1], then the sRGB curve (the default encoding)
  }
  return p;
}

std::vector<uint8_t> to_ldr(const Image& img, const PreviewSettings& s) {
  if (s.kind == PreviewKind::Photographic) return photographic(img, s.tonemap);
  const auto& px = img.pixels();
  std::vector<uint8_t> out(px.size() * 3);
  for (size_t i = 0; i < px.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = px[i][c];
      float e;
      if (s.kind == PreviewKind::CourseLdr) {
        e = v / 255.0f;  // radiance is already on the 0-255 scale (spec §10)
        if (s.course_ldr_srgb) e = srgb_encode(std::clamp(e, 0.0f, 1.0f));
      } else {
        const float cl = std::clamp(v, 0.0f, 1.0f);
        e = s.srgb ? srgb_encode(cl) : std::pow(cl, 1.0f / s.gamma);
      }
      out[i * 3 + size_t(c)] = quantize(e);
    }
  return out;
}

}  // namespace kiln
