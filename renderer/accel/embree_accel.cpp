#include "renderer/accel/embree_accel.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "renderer/accel/alpha.h"
#include "renderer/accel/object_ray.h"
#include "renderer/accel/quadric_intersect.h"
#include "renderer/accel/shape_bounds.h"
#include "renderer/accel/sphere_intersect.h"
#include "renderer/accel/surface_point.h"
#include "renderer/accel/traceable_ray.h"

namespace kiln {
namespace {

// Time steps of an animated shape's user geometry: Embree interpolates the bounds of neighbouring steps linearly,
// so each step's box holds the shape over the steps on either side (AnimatedTransform::motion_bounds), and a
// rotation gets a step per this angle so that the boxes stay tight.
constexpr float kAnimatedStepTurn = 3.14159265f / 16.0f;
constexpr unsigned kMaxTimeSteps = 129;  // Embree's limit

unsigned animated_time_steps(const AnimatedTransform& m) {
  return std::min(kMaxTimeSteps, 2u + unsigned(std::ceil(m.rotation_angle() / kAnimatedStepTurn)));
}

// A box holding an animated shape over the time steps next to `step` of `steps`.
RTCBounds animated_step_bounds(const AnimatedTransform& m, const Bounds3f& object, unsigned step, unsigned steps) {
  const float h = 1.0f / float(steps - 1), t = float(step) * h;
  const Bounds3f b = m.motion_bounds(object, t - h, t + h);
  return RTCBounds{b.lo.x, b.lo.y, b.lo.z, 0.0f, b.hi.x, b.hi.y, b.hi.z, 0.0f};
}

// What a sphere's user-geometry callbacks need; the transform is skipped for plain spheres.
// A moving sphere (motion non-zero) has two time steps; the callbacks move the ray back by the sphere's offset at
// the ray's time instead of moving the sphere. An animated one (pbrt's interpolated transform) takes the ray into
// its space at the ray's time.
struct SphereData {
  const SphereShape* shape = nullptr;
  bool has_transform = false;
  Transform to_object;
  Vec3f motion{0.0f};
  const AnimatedTransform* animated = nullptr;
  unsigned steps = 2;
};

// A user geometry's bounds at a time step: its time-0 bounds moved by its motion (time steps 0 and 1 are the
// shutter's ends).
void store_bounds(const RTCBoundsFunctionArguments* args, Bounds3f b, Vec3f motion) {
  const Vec3f offset = motion * float(args->timeStep);
  b.lo += offset;
  b.hi += offset;
  *args->bounds_o = RTCBounds{b.lo.x, b.lo.y, b.lo.z, 0.0f, b.hi.x, b.hi.y, b.hi.z, 0.0f};
}

void sphere_bounds_cb(const RTCBoundsFunctionArguments* args) {
  const auto* s = static_cast<const SphereData*>(args->geometryUserPtr);
  if (s->animated) {
    const Bounds3f object(s->shape->center - Vec3f(s->shape->radius), s->shape->center + Vec3f(s->shape->radius));
    *args->bounds_o = animated_step_bounds(*s->animated, object, args->timeStep, s->steps);
    return;
  }
  store_bounds(args, sphere_world_bounds(*s->shape), s->motion);
}

inline void sphere_object_ray(const SphereData& s, Vec3f& o, Vec3f& d, float time) {
  if (s.animated)
    to_object_space(s.animated->at(time).inverse(), o, d);
  else if (s.has_transform)
    to_object_space(s.to_object, o, d);
}

void sphere_intersect_cb(const RTCIntersectFunctionNArguments* args) {
  const auto* s = static_cast<const SphereData*>(args->geometryUserPtr);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3f wo = Vec3f(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                           RTCRayN_org_z(ray, args->N, i)) -
                     s->motion * RTCRayN_time(ray, args->N, i);
    const Vec3f wd(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
    Vec3f o = wo, d = wd;
    const float time = RTCRayN_time(ray, args->N, i);
    sphere_object_ray(*s, o, d, time);
    const auto t = intersect_sphere(o, d, s->shape->center, s->shape->radius, RTCRayN_tnear(ray, args->N, i),
                                    RTCRayN_tfar(ray, args->N, i));
    if (!t) continue;
    const Vec3f n = s->animated ? sphere_world_normal(*s->shape, s->animated->at(time), Ray{wo, wd}, *t)
                                : sphere_world_normal(*s->shape, Ray{wo, wd}, *t);
    RTCRayN_tfar(ray, args->N, i) = *t;
    RTCHitN_Ng_x(hit, args->N, i) = n.x;
    RTCHitN_Ng_y(hit, args->N, i) = n.y;
    RTCHitN_Ng_z(hit, args->N, i) = n.z;
    RTCHitN_u(hit, args->N, i) = 0.0f;
    RTCHitN_v(hit, args->N, i) = 0.0f;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void sphere_occluded_cb(const RTCOccludedFunctionNArguments* args) {
  const auto* s = static_cast<const SphereData*>(args->geometryUserPtr);
  RTCRayN* ray = args->ray;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    Vec3f o = Vec3f(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i), RTCRayN_org_z(ray, args->N, i)) -
              s->motion * RTCRayN_time(ray, args->N, i);
    Vec3f d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
    sphere_object_ray(*s, o, d, RTCRayN_time(ray, args->N, i));
    if (intersect_sphere(o, d, s->shape->center, s->shape->radius, RTCRayN_tnear(ray, args->N, i),
                         RTCRayN_tfar(ray, args->N, i)))
      RTCRayN_tfar(ray, args->N, i) = -kInfinity;  // Embree's "occluded" marker
  }
}

// The intersect context Kiln passes to every query: Embree hands it to the callbacks, which read the world-space
// ray from it (the alpha hash is taken of the ray as the caller gave it, also inside instances, where Embree's own
// ray is in object space).
struct QueryContext {
  RTCIntersectContext rtc;  // first member: Embree's pointer to it is a pointer to the whole
  const Ray* world_ray;     // the caller's, alive for the query
};

const Ray& world_ray_of(const RTCIntersectContext* context) {
  return *reinterpret_cast<const QueryContext*>(context)->world_ray;
}

// An animated instance (pbrt's interpolated transform) as user geometry around its prototype's scene: the ray goes
// into object space at its own time and is traced there, so Embree and the in-house BVH move it by the same
// transform (Embree's own instance motion would interpolate differently).
struct AnimatedInstanceData {
  const AnimatedTransform* motion = nullptr;
  RTCScene prototype = nullptr;
  Bounds3f object_bounds;
  unsigned steps = 2;
};

void animated_instance_bounds_cb(const RTCBoundsFunctionArguments* args) {
  const auto* a = static_cast<const AnimatedInstanceData*>(args->geometryUserPtr);
  *args->bounds_o = animated_step_bounds(*a->motion, a->object_bounds, args->timeStep, a->steps);
}

// The ray of lane i in the instance's object space (tfar as it stands: nearer hits found so far still count).
RTCRayHit object_ray(const AnimatedInstanceData& a, RTCRayN* ray, unsigned n, unsigned i) {
  Vec3f o(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i));
  Vec3f d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
  const float time = RTCRayN_time(ray, n, i);
  to_object_space(a.motion->at(time).inverse(), o, d);
  RTCRayHit rh{};
  rh.ray = {o.x, o.y, o.z, RTCRayN_tnear(ray, n, i), d.x, d.y, d.z, time, RTCRayN_tfar(ray, n, i), 0xffffffffu, 0, 0};
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// The context of the query inside the prototype: the caller's world-space ray for alpha, and the instance's shape as
// instID (Embree reports it with the prototype's hits, as for its own instances), so alpha asks about the instance.
QueryContext prototype_context(const RTCIntersectContext* outer, unsigned instance_shape) {
  QueryContext c{};
  rtcInitIntersectContext(&c.rtc);
  c.rtc.instID[0] = instance_shape;
  c.world_ray = &world_ray_of(outer);
  return c;
}

void animated_instance_intersect_cb(const RTCIntersectFunctionNArguments* args) {
  const auto* a = static_cast<const AnimatedInstanceData*>(args->geometryUserPtr);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    alignas(16) RTCRayHit rh = object_ray(*a, ray, args->N, i);
    QueryContext ctx = prototype_context(args->context, args->geomID);
    rtcIntersect1(a->prototype, &ctx.rtc, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    RTCRayN_tfar(ray, args->N, i) = rh.ray.tfar;
    RTCHitN_Ng_x(hit, args->N, i) = rh.hit.Ng_x;
    RTCHitN_Ng_y(hit, args->N, i) = rh.hit.Ng_y;
    RTCHitN_Ng_z(hit, args->N, i) = rh.hit.Ng_z;
    RTCHitN_u(hit, args->N, i) = rh.hit.u;
    RTCHitN_v(hit, args->N, i) = rh.hit.v;
    RTCHitN_primID(hit, args->N, i) = rh.hit.primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void animated_instance_occluded_cb(const RTCOccludedFunctionNArguments* args) {
  const auto* a = static_cast<const AnimatedInstanceData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    alignas(16) RTCRayHit rh = object_ray(*a, args->ray, args->N, i);
    QueryContext ctx = prototype_context(args->context, args->geomID);
    rtcOccluded1(a->prototype, &ctx.rtc, &rh.ray);
    if (rh.ray.tfar == -kInfinity) RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;
  }
}

// What a quadric's user-geometry callbacks need (as SphereData).
struct QuadricData {
  const WorldGeometry* geometry = nullptr;
  uint32_t shape = 0;
  const QuadricShape* quadric = nullptr;
  Transform to_object;
  Vec3f motion{0.0f};
  bool alpha = false;
  const AnimatedTransform* animated = nullptr;
  unsigned steps = 2;
};

void quadric_bounds_cb(const RTCBoundsFunctionArguments* args) {
  const auto* q = static_cast<const QuadricData*>(args->geometryUserPtr);
  if (q->animated) {
    const Shape& s = q->geometry->shapes[q->shape];
    *args->bounds_o = animated_step_bounds(*q->animated, shape_object_bounds(*q->geometry, s), args->timeStep, q->steps);
    return;
  }
  store_bounds(args, quadric_world_bounds(*q->quadric), q->motion);
}

// Lane i of a ray packet against the quadric (object space), its alpha test included.
std::optional<QuadricHit> quadric_lane(const QuadricData& q, const RTCIntersectContext* context, RTCRayN* ray,
                                       unsigned n, unsigned i) {
  const float time = RTCRayN_time(ray, n, i);
  Vec3f o = Vec3f(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)) - q.motion * time;
  Vec3f d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
  to_object_space(q.animated ? q.animated->at(time).inverse() : q.to_object, o, d);
  return intersect_quadric(q.quadric->quadric, o, d, RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i),
                           [&](const QuadricHit& h) {
                             return !q.alpha || alpha_keeps(*q.geometry, world_ray_of(context), q.shape, 0, h.uv,
                                                            h.root);
                           });
}

void quadric_intersect_cb(const RTCIntersectFunctionNArguments* args) {
  const auto* q = static_cast<const QuadricData*>(args->geometryUserPtr);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const auto h = quadric_lane(*q, args->context, ray, args->N, i);
    if (!h) continue;
    // The normal is computed once for the closest hit (EmbreeAccel::intersect), as the BVH does.
    RTCRayN_tfar(ray, args->N, i) = h->t;
    RTCHitN_Ng_x(hit, args->N, i) = 0.0f;
    RTCHitN_Ng_y(hit, args->N, i) = 0.0f;
    RTCHitN_Ng_z(hit, args->N, i) = 1.0f;
    RTCHitN_u(hit, args->N, i) = h->uv.x;
    RTCHitN_v(hit, args->N, i) = h->uv.y;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void quadric_occluded_cb(const RTCOccludedFunctionNArguments* args) {
  const auto* q = static_cast<const QuadricData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (quadric_lane(*q, args->context, args->ray, args->N, i)) RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;
  }
}

// Alpha on triangles: Embree asks about every candidate hit; a rejected one (valid = 0) lets traversal go on. The
// shape is the instance's when the triangle belongs to an instanced prototype.
void triangle_alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const WorldGeometry*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned inst = RTCHitN_instID(args->hit, args->N, i, 0);
    const uint32_t shape = inst != RTC_INVALID_GEOMETRY_ID ? inst : RTCHitN_geomID(args->hit, args->N, i);
    const Vec2f b(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    if (!alpha_keeps(*g, world_ray_of(args->context), shape, RTCHitN_primID(args->hit, args->N, i), b, 0))
      args->valid[i] = 0;
  }
}

// Embree's SSE loads may read up to 12 bytes past the last float3/uint3 element, so a caller's array is shared
// only when its allocation extends at least one element beyond its size.
template <typename T>
bool shareable(const std::vector<T>& v) {
  return v.capacity() > v.size();
}

void error_cb(void* user, RTCError, const char* message) {
  auto* last = static_cast<std::string*>(user);
  *last = message ? message : "unknown Embree error";
}

}  // namespace

struct EmbreeAccel::Impl {
  const WorldGeometry& geometry;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<RTCScene> prototype_scenes;  // null for prototypes no instance uses
  std::vector<SphereData> sphere_data;
  std::vector<AnimatedInstanceData> animated_instances;
  std::vector<QuadricData> quadric_data;
  std::string last_error;
  std::atomic<int64_t> bytes{0};
  double build_seconds = 0;

  explicit Impl(const WorldGeometry& g) : geometry(g) {}
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    for (RTCScene s : prototype_scenes)
      if (s) rtcReleaseScene(s);
    if (device) rtcReleaseDevice(device);
  }

  void check(const char* what) {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
      throw Error(std::string("Embree: ") + what +
                  " failed: " + (last_error.empty() ? "error code " + std::to_string(int(e)) : last_error));
  }

  // motion non-zero: two time steps, the second vertex buffer holding the vertices moved by it (Embree
  // interpolates linearly between them, which is the translation at every instant).
  // alpha: the mesh has an alpha cut-out (filter functions installed; shapes without one pay nothing).
  RTCGeometry triangle_geometry(const TriangleMesh& m, Vec3f motion = Vec3f(0.0f), bool alpha = false) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (alpha) {
      rtcSetGeometryUserData(geom, const_cast<WorldGeometry*>(&geometry));
      rtcSetGeometryIntersectFilterFunction(geom, triangle_alpha_filter);
      rtcSetGeometryOccludedFilterFunction(geom, triangle_alpha_filter);
    }
    const size_t nv = m.p.size(), nt = m.triangle_count();
    const bool moving = motion.x != 0.0f || motion.y != 0.0f || motion.z != 0.0f;
    if (moving) {
      rtcSetGeometryTimeStepCount(geom, 2);
      auto* end = static_cast<Vec3f*>(
          rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 1, RTC_FORMAT_FLOAT3, sizeof(Vec3f), nv));
      if (end)
        for (size_t i = 0; i < nv; ++i) end[i] = m.p[i] + motion;
    }
    if (shareable(m.p)) {
      rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.p.data(), 0, sizeof(Vec3f), nv);
    } else {
      void* dst = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3f), nv);
      if (dst) std::memcpy(dst, m.p.data(), nv * sizeof(Vec3f));
    }
    if (shareable(m.idx)) {
      rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.idx.data(), 0,
                                 3 * sizeof(uint32_t), nt);
    } else {
      void* dst = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt);
      if (dst) std::memcpy(dst, m.idx.data(), nt * 3 * sizeof(uint32_t));
    }
    rtcCommitGeometry(geom);
    check("creating a triangle geometry");
    return geom;
  }

  RTCGeometry animated_instance_geometry(const AnimatedTransform& motion, RTCScene proto, const Bounds3f& object) {
    animated_instances.push_back({&motion, proto, object, animated_time_steps(motion)});
    return user_geometry(&animated_instances.back(), animated_instances.back().steps, animated_instance_bounds_cb,
                         animated_instance_intersect_cb, animated_instance_occluded_cb);
  }

  // One primitive computed by callbacks on `data`; time_steps > 0 for a moving one (the shutter's ends, or more for
  // an animated transform).
  RTCGeometry user_geometry(void* data, unsigned time_steps, RTCBoundsFunction bounds,
                            RTCIntersectFunctionN intersect, RTCOccludedFunctionN occluded) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    if (time_steps > 0) rtcSetGeometryTimeStepCount(geom, time_steps);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, data);
    rtcSetGeometryBoundsFunction(geom, bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, intersect);
    rtcSetGeometryOccludedFunction(geom, occluded);
    rtcCommitGeometry(geom);
    return geom;
  }

  RTCScene new_scene() {
    RTCScene s = rtcNewScene(device);
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    return s;
  }

  void build() {
    const auto start = std::chrono::steady_clock::now();
    device = rtcNewDevice(nullptr);
    if (!device)
      throw Error("Embree: cannot create a device (error code " + std::to_string(int(rtcGetDeviceError(nullptr))) +
                  ")");
    rtcSetDeviceErrorFunction(device, error_cb, &last_error);
    rtcSetDeviceMemoryMonitorFunction(
        device,
        [](void* user, ssize_t delta, bool) {
          static_cast<std::atomic<int64_t>*>(user)->fetch_add(int64_t(delta), std::memory_order_relaxed);
          return true;
        },
        &bytes);
    scene = new_scene();
    sphere_data.reserve(geometry.spheres.size());  // callbacks keep pointers into it
    animated_instances.reserve(geometry.instances.size());
    quadric_data.reserve(geometry.quadrics.size());
    prototype_scenes.assign(geometry.prototypes.size(), nullptr);

    const auto& shapes = geometry.shapes;
    for (uint32_t id = 0; id < shapes.size(); ++id) {
      const Shape& s = shapes[id];
      RTCGeometry geom = nullptr;
      if (s.kind == ShapeKind::Mesh) {
        if (geometry.meshes[s.index].triangle_count() == 0) continue;
        geom = triangle_geometry(geometry.meshes[s.index], s.motion, s.alpha);
      } else if (s.kind == ShapeKind::Sphere) {
        const SphereShape& sph = geometry.spheres[s.index];
        const AnimatedTransform* animated = s.animated >= 0 ? &geometry.motions[size_t(s.animated)] : nullptr;
        const unsigned steps = animated ? animated_time_steps(*animated) : 2;
        sphere_data.push_back({&sph, !sph.to_world.is_identity(), sph.to_world.inverse(), s.motion, animated, steps});
        geom = user_geometry(&sphere_data.back(), s.moving() ? steps : 0, sphere_bounds_cb, sphere_intersect_cb,
                             sphere_occluded_cb);
      } else if (s.kind == ShapeKind::Quadric) {
        const QuadricShape& q = geometry.quadrics[s.index];
        const AnimatedTransform* animated = s.animated >= 0 ? &geometry.motions[size_t(s.animated)] : nullptr;
        const unsigned steps = animated ? animated_time_steps(*animated) : 2;
        quadric_data.push_back({&geometry, id, &q, q.to_world.inverse(), s.motion, s.alpha, animated, steps});
        geom = user_geometry(&quadric_data.back(), s.moving() ? steps : 0, quadric_bounds_cb, quadric_intersect_cb,
                             quadric_occluded_cb);
      } else {
        const MeshInstance& inst = geometry.instances[s.index];
        if (geometry.prototypes[inst.prototype].triangle_count() == 0) continue;
        RTCScene& proto = prototype_scenes[inst.prototype];
        if (!proto) {
          proto = new_scene();
          // The instances of one prototype share its alpha (pbrt's object instances share their shapes').
          RTCGeometry tri = triangle_geometry(geometry.prototypes[inst.prototype], Vec3f(0.0f), s.alpha);
          rtcAttachGeometryByID(proto, tri, 0);
          rtcReleaseGeometry(tri);
          rtcCommitScene(proto);
          check("building an instance prototype");
        }
        if (s.animated >= 0) {
          geom = animated_instance_geometry(geometry.motions[size_t(s.animated)], proto,
                                            mesh_bounds(geometry.prototypes[inst.prototype]));
          rtcAttachGeometryByID(scene, geom, id);
          rtcReleaseGeometry(geom);
          continue;
        }
        geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, proto);
        float xfm[12];
        const auto& m = inst.to_world.matrix().m;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 4; ++c) xfm[4 * r + c] = m[r][c];
        if (s.moving()) {  // the transforms at the shutter's ends, interpolated by Embree
          rtcSetGeometryTimeStepCount(geom, 2);
          rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
          for (int r = 0; r < 3; ++r) xfm[4 * r + 3] += s.motion[r];
          rtcSetGeometryTransform(geom, 1, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
        } else {
          rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
        }
        rtcCommitGeometry(geom);
      }
      rtcAttachGeometryByID(scene, geom, id);
      rtcReleaseGeometry(geom);
    }
    rtcCommitScene(scene);
    check("building the scene");
    build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

EmbreeAccel::EmbreeAccel(const WorldGeometry& geometry) : impl_(std::make_unique<Impl>(geometry)) { impl_->build(); }

EmbreeAccel::~EmbreeAccel() = default;

namespace {
RTCRay to_rtc(const Ray& r) {
  RTCRay x;
  x.org_x = r.o.x;
  x.org_y = r.o.y;
  x.org_z = r.o.z;
  x.tnear = r.tmin;
  x.dir_x = r.d.x;
  x.dir_y = r.d.y;
  x.dir_z = r.d.z;
  x.time = r.time;
  x.tfar = r.tmax;
  x.mask = 0xffffffffu;
  x.id = 0;
  x.flags = 0;
  return x;
}
}  // namespace

bool EmbreeAccel::intersect(const Ray& ray, Hit& hit) const {
  if (!traceable(ray)) return false;
  QueryContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.world_ray = &ray;
  RTCRayHit rh;
  rh.ray = to_rtc(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx.rtc, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const WorldGeometry& g = impl_->geometry;
  hit.t = rh.ray.tfar;
  hit.shape = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID;
  const Shape& s = g.shapes[hit.shape];
  if (s.kind == ShapeKind::Sphere) {
    hit.prim = 0;
    hit.u = hit.v = 0.0f;
    hit.ng = Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  } else if (s.kind == ShapeKind::Quadric) {
    hit.prim = 0;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    Ray back = ray;  // a moving quadric is hit where it is at the ray's time
    if (s.translates()) back.o -= s.offset_at(ray.time);
    hit.ng = quadric_world_normal(quadric_at(g, s, ray.time), back, hit.t);
  } else {
    hit.prim = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    // Recomputed from the vertices so both accelerators report the same (v1-v0)x(v2-v0) convention.
    hit.ng = triangle_world_normal(g, hit.shape, hit.prim, ray.time);
  }
  return true;
}

bool EmbreeAccel::occluded(const Ray& ray) const {
  if (!traceable(ray)) return false;
  QueryContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.world_ray = &ray;
  RTCRay r = to_rtc(ray);
  rtcOccluded1(impl_->scene, &ctx.rtc, &r);
  return r.tfar == -kInfinity;
}

AccelStats EmbreeAccel::stats() const {
  return {"embree", impl_->build_seconds, size_t(std::max<int64_t>(0, impl_->bytes.load()))};
}

}  // namespace kiln
