// The integrators: Kiln's own path tracer is what every scene gets under Kiln's rules (its volumetric path tracer when
// the scene has participating media); the course path tracer and the course ray tracer reproduce the CENG795
// reference renderer. Their settings (renderer/integrators/settings.h) say which one renders a camera. Every
// integrator is a pure function of (render context, camera ray, per-sample sampler): it reads the world and the
// context and writes nothing but its counters, so output is independent of threads, tile order and of other renders
// of the same world.
#pragma once
#include <cstdint>

#include "core/sampler.h"
#include "renderer/film/visible_surface.h"
#include "renderer/integrators/render_context.h"
#include "renderer/integrators/settings.h"
#include "renderer/world/ray_query.h"

namespace kiln {

// Sampler dimensions (core/sampler.h): the pixel position and lens come first, then the integrator's requests
// (renderer/integrators/path_vertex.h lays out the path tracers' per-vertex requests).
inline constexpr uint32_t kPixelDimension = 0;
inline constexpr uint32_t kLensDimension = 1;
inline constexpr uint32_t kFirstPathDimension = 2;
// The shutter time of a camera sample (motion blur), one per path: a dedicated stream (Sampler::dedicated_1d).
inline constexpr uint32_t kTimeStream = 0x74696d65u;  // "time"

// Radiance along a camera ray (the sampler is positioned at kFirstPathDimension), one overload per integrator's
// settings. film: the ray's pixel on the image, its centre in [0, 1]^2 (x to the right, y down): where a camera ray
// that misses looks up the background texture (renderer/integrators/path_vertex.h, camera_background). visible:
// where to record what the camera sample sees for the AOVs (renderer/film/visible_surface.h), or null; recording
// draws nothing from the sampler, so the radiance is the same either way.
Rgb integrate(const RenderContext& ctx, const PathSettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible);
Rgb integrate(const RenderContext& ctx, const VolPathSettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible);
Rgb integrate(const RenderContext& ctx, const CoursePathSettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible);
Rgb integrate(const RenderContext& ctx, const CourseRaySettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible);

// The integrator the context's settings name, with their firefly clamp.
Rgb trace(const RenderContext& ctx, const Ray& ray, Vec2f film, Sampler& sampler, RayCounters& c,
          VisibleSurface* visible = nullptr);

// The film position of pixel (x, y) (y = 0 the top row) of a width x height image: its centre, (x + 1/2) / width,
// (y + 1/2) / height. The CENG795 spec (§1, BackgroundTexture) maps the background image to the image plane with
// "u = x/width, v = y/height"; x, y are read as the pixel's centre, so an image of the output's size shows texel
// (x, y) at pixel (x, y) whatever the rounding, and v grows downwards like the image's rows (the spec's pixel j and
// OpenImageIO's t both count from the top). One position per pixel, not per sample: the background is not blurred
// by the pixel filter and every sample of a pixel sees the same texel.
inline Vec2f pixel_film_position(int x, int y, int width, int height) {
  return {(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)};
}

}  // namespace kiln
