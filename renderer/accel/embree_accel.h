// Embree 3 accelerator. One device and one top-level scene: world meshes as triangle geometries (sharing the
// caller's vertex/index arrays when their allocation has the padding Embree's SSE loads need), spheres and
// ellipsoids as user geometries calling sphere_intersect.h, quadrics as user geometries calling
// quadric_intersect.h, instances as instance geometries over one committed scene per referenced prototype. Shapes
// with an alpha cut-out get intersection and occlusion filter functions (triangles) or test it in their callback
// (quadrics), through renderer/accel/alpha.h; the others have none. Embree geometry ids are indices into
// WorldGeometry::shapes. The scene is built with RTC_SCENE_FLAG_ROBUST (no accuracy-reducing shortcuts) and
// RTC_BUILD_QUALITY_HIGH.
#pragma once
#include <memory>

#include "renderer/accel/accelerator.h"

namespace kiln {

class EmbreeAccel final : public Accelerator {
 public:
  // Throws kiln::Error when Embree cannot create the device or build the scene.
  explicit EmbreeAccel(const WorldGeometry& geometry);
  ~EmbreeAccel() override;
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  bool intersect(const Ray& ray, Hit& hit) const override;
  bool occluded(const Ray& ray) const override;
  AccelStats stats() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kiln
