#include "renderer/accel/check_bvh.h"

#include <cstdio>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/frame.h"
#include "core/sampling.h"
#include "renderer/accel/bvh.h"
#include "renderer/accel/embree_accel.h"
#include "renderer/accel/hit_point.h"
#include "renderer/accel/shape_bounds.h"

namespace kiln {
namespace {

enum class Outcome : uint8_t { None, Agree, Tie, Disagree };  // None: ray not shot

struct RayOutcome {
  Outcome camera = Outcome::None, bounce = Outcome::None, shadow = Outcome::None;
};

float ulp(float x) {
  x = std::abs(x);
  return std::nextafter(x, kInfinity) - x;
}

bool distances_agree(const Ray& r, float a, float b) {
  const float dt = std::abs(a - b);
  if (dt <= kCheckBvhDistanceTolerance * std::max(std::abs(a), std::abs(b))) return true;
  return dt * length(r.d) <= kCheckBvhHitPointUlps * ulp(max_component(abs(r.at(a))));
}

Outcome compare(const Ray& r, bool ha, const Hit& a, bool hb, const Hit& b) {
  if (ha != hb) return Outcome::Disagree;
  if (!ha) return Outcome::Agree;
  if (!distances_agree(r, a.t, b.t)) return Outcome::Disagree;
  if (a.shape != b.shape || a.prim != b.prim) return Outcome::Tie;
  return Outcome::Agree;
}

std::string describe(const char* kind, size_t i, const Ray& r, bool ha, const Hit& a, bool hb, const Hit& b) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s ray %zu o=(%.9g, %.9g, %.9g) d=(%.9g, %.9g, %.9g) tmax=%.9g: embree %s t=%.9g shape=%u prim=%u, "
                "bvh %s t=%.9g shape=%u prim=%u",
                kind, i, double(r.o.x), double(r.o.y), double(r.o.z), double(r.d.x), double(r.d.y), double(r.d.z),
                double(r.tmax), ha ? "hit" : "miss", double(a.t), a.shape, a.prim, hb ? "hit" : "miss", double(b.t),
                b.shape, b.prim);
  return buf;
}

void count(CheckBvhKind& k, Outcome o) {
  if (o == Outcome::None) return;
  ++k.rays;
  if (o == Outcome::Disagree) ++k.disagreements;
  if (o == Outcome::Tie) ++k.edge_ties;
}

std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out;
}

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string kinds_json(size_t CheckBvhKind::*field, const CheckBvhReport& r) {
  return "{\"camera\": " + std::to_string(r.camera.*field) + ", \"bounce\": " + std::to_string(r.bounce.*field) +
         ", \"shadow\": " + std::to_string(r.shadow.*field) +
         ", \"total\": " + std::to_string(r.camera.*field + r.bounce.*field + r.shadow.*field) + "}";
}

}  // namespace

std::string CheckBvhReport::to_json() const {
  std::string hist;
  for (size_t i = 0; i < bvh.leaf_size_histogram.size(); ++i)
    hist += (i ? ", " : "") + std::to_string(bvh.leaf_size_histogram[i]);
  std::string s = "{\n";
  s += "  \"passed\": " + std::string(passed ? "true" : "false") + ",\n";
  s += "  \"rays\": " + kinds_json(&CheckBvhKind::rays, *this) + ",\n";
  s += "  \"disagreements\": " + kinds_json(&CheckBvhKind::disagreements, *this) + ",\n";
  s += "  \"edge_ties\": " + kinds_json(&CheckBvhKind::edge_ties, *this) + ",\n";
  s += "  \"max_disagreement_rate\": " + num(kCheckBvhMaxDisagreementRate) + ",\n";
  s += "  \"distance_tolerance\": " + num(kCheckBvhDistanceTolerance) + ",\n";
  s += "  \"hit_point_ulps\": " + num(kCheckBvhHitPointUlps) + ",\n";
  s += "  \"bvh\": {\"sah_cost\": " + num(bvh.sah_cost) + ", \"nodes\": " + std::to_string(bvh.nodes) +
       ", \"leaves\": " + std::to_string(bvh.leaves) + ", \"max_depth\": " + std::to_string(bvh.max_depth) +
       ", \"primitives\": " + std::to_string(bvh.primitives) + ", \"leaf_size_histogram\": [" + hist + "]},\n";
  s += "  \"build_seconds\": {\"embree\": " + num(embree_stats.build_seconds) + ", \"bvh\": " +
       num(bvh_stats.build_seconds) + "},\n";
  s += "  \"bytes\": {\"embree\": " + std::to_string(embree_stats.bytes) + ", \"bvh\": " +
       std::to_string(bvh_stats.bytes) + "},\n";
  s += "  \"first_disagreement\": \"" + json_escape(first_disagreement) + "\"\n";
  s += "}\n";
  return s;
}

CheckBvhReport check_bvh(const WorldGeometry& geometry, const std::function<Ray(size_t i, Rng&)>& camera_ray,
                         const CheckBvhOptions& options) {
  const EmbreeAccel embree(geometry);
  const Bvh bvh(geometry);
  return check_bvh(geometry, embree, bvh, camera_ray, options);
}

CheckBvhReport check_bvh(const WorldGeometry& geometry, const Accelerator& embree, const Bvh& bvh,
                         const std::function<Ray(size_t i, Rng&)>& camera_ray, const CheckBvhOptions& options) {
  const Bounds3f scene = geometry_bounds(geometry);
  std::vector<RayOutcome> outcomes(options.rays);
  std::vector<std::string> notes(options.rays);
  tbb::parallel_for(size_t(0), options.rays, [&](size_t i) {
    Rng rng(options.seed, i);
    RayOutcome& out = outcomes[i];
    const Ray cam = camera_ray(i, rng);
    Hit ea, ba;
    const bool he = embree.intersect(cam, ea), hb = bvh.intersect(cam, ba);
    out.camera = compare(cam, he, ea, hb, ba);
    if (out.camera == Outcome::Disagree) notes[i] = describe("camera", i, cam, he, ea, hb, ba);
    if (!he) return;
    const float len = length(ea.ng);
    if (!(len > 0.0f) || !std::isfinite(len)) return;  // degenerate triangle: no direction to leave in
    const Vec3f ng = ea.ng / len;
    const Vec3f p = hit_point(geometry, cam, ea);

    const Frame frame(face_forward(ng, -cam.d));
    const Ray bounce = spawn_ray(p, ng, frame.to_world(sample_cosine_hemisphere(rng.next_2d())));
    Hit eb, bb;
    const bool he2 = embree.intersect(bounce, eb), hb2 = bvh.intersect(bounce, bb);
    out.bounce = compare(bounce, he2, eb, hb2, bb);
    if (out.bounce == Outcome::Disagree && notes[i].empty()) notes[i] = describe("bounce", i, bounce, he2, eb, hb2, bb);

    const Vec3f u(rng.next_float(), rng.next_float(), rng.next_float());
    const Vec3f target = scene.lo + scene.diagonal() * u;
    const Ray shadow = spawn_ray_to(p, ng, target);
    const bool oe = embree.occluded(shadow), ob = bvh.occluded(shadow);
    out.shadow = oe == ob ? Outcome::Agree : Outcome::Disagree;
    if (oe != ob && notes[i].empty()) {
      Hit a, b;
      a.t = b.t = oe ? 0.0f : kInfinity;
      notes[i] = describe("shadow", i, shadow, oe, a, ob, b);
    }
  });

  CheckBvhReport r;
  for (size_t i = 0; i < options.rays; ++i) {
    count(r.camera, outcomes[i].camera);
    count(r.bounce, outcomes[i].bounce);
    count(r.shadow, outcomes[i].shadow);
    if (r.first_disagreement.empty() && !notes[i].empty()) r.first_disagreement = notes[i];
  }
  r.bvh = bvh.bvh_stats().world;
  r.embree_stats = embree.stats();
  r.bvh_stats = bvh.stats();
  r.passed = double(r.total_disagreements()) <= kCheckBvhMaxDisagreementRate * double(r.total_rays());
  return r;
}

}  // namespace kiln
