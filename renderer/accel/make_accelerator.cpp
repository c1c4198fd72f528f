#include "renderer/accel/accelerator.h"
#include "renderer/accel/bvh.h"
#include "renderer/accel/embree_accel.h"

namespace kiln {

std::unique_ptr<Accelerator> make_accelerator(AccelKind kind, const WorldGeometry& geometry) {
  if (kind == AccelKind::Bvh) return std::make_unique<Bvh>(geometry);
  return std::make_unique<EmbreeAccel>(geometry);
}

}  // namespace kiln
