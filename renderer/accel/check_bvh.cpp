#include "renderer/accel/check_bvh.h"

#include <tbb/parallel_for.h>

#include <cstdio>
#include <vector>

#include "core/frame.h"
#include "core/sampling.h"
#include "renderer/accel/alpha.h"
#include "renderer/accel/bvh.h"
#include "renderer/accel/embree_accel.h"
#include "renderer/accel/exact_hit.h"
#include "renderer/accel/surface_point.h"
#include "renderer/accel/shape_bounds.h"

namespace kiln {
namespace {

// None: ray not shot. Disagreements carry the referee's verdict.
enum class Outcome : uint8_t { None, Agree, Tie, EmbreeFault, BvhFault, Unresolved };
bool is_disagreement(Outcome o) { return o >= Outcome::EmbreeFault; }

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

// What exact arithmetic says about a reported hit: beside the primitive or out of [tmin, tmax] (spurious), clearly
// on it (real), or on it / beside it within float noise of an edge or silhouette (borderline).
enum class Verdict { Real, Spurious, Borderline };
Verdict judge(const ExactHit& e) {
  if (e.hit) return e.near_edge ? Verdict::Borderline : Verdict::Real;
  return e.near_edge && e.in_range ? Verdict::Borderline : Verdict::Spurious;
}

// How close the alpha hash may come to the opacity before the alpha test counts as borderline: float hit
// coordinates differ from exact ones by ~1e-7, which moves a bilinearly filtered opacity by far less.
constexpr float kAlphaNoise = 1e-4f;

// The exact hit on a primitive, with the alpha test of its shape applied at the exact hit coordinates: a crossing the
// test passes through is no hit (borderline when the hash lies within kAlphaNoise of the opacity).
ExactHit exact_hit_with_alpha(const WorldGeometry& g, const Ray& r, uint32_t shape, uint32_t prim) {
  ExactHit e = exact_hit(g, r, shape, prim);
  if (!e.hit || !g.shapes[shape].alpha) return e;
  const float a = g.alpha.opacity(g.alpha.world, shape, prim, e.where, r.time);
  const float u = alpha_hash(r, shape, prim, e.root);
  if (a > 0.0f && a < 1.0f && std::abs(u - a) <= kAlphaNoise) e.near_edge = true;
  e.hit = alpha_keeps(g, r, shape, prim, e.where, e.root);
  return e;
}

// Which of two disagreeing closest-hit answers (a: Embree, b: BVH) exact arithmetic contradicts.
Outcome referee(const WorldGeometry& g, const Ray& r, bool ha, const Hit& a, bool hb, const Hit& b) {
  const ExactHit ea = ha ? exact_hit_with_alpha(g, r, a.shape, a.prim) : ExactHit{};
  const ExactHit eb = hb ? exact_hit_with_alpha(g, r, b.shape, b.prim) : ExactHit{};
  const Verdict va = ha ? judge(ea) : Verdict::Real, vb = hb ? judge(eb) : Verdict::Real;
  const bool a_bad = va == Verdict::Spurious, b_bad = vb == Verdict::Spurious;
  if (a_bad || b_bad) return a_bad && b_bad ? Outcome::Unresolved : a_bad ? Outcome::EmbreeFault : Outcome::BvhFault;
  if (ha != hb) {  // one missed the other's hit: its fault unless that hit is a graze
    if ((ha ? va : vb) == Verdict::Borderline) return Outcome::Unresolved;
    return ha ? Outcome::BvhFault : Outcome::EmbreeFault;
  }
  // Both hit something real: the one reporting the farther primitive is wrong, unless the nearer one is a graze;
  // at the same exact distance, the less accurate t is.
  if (std::abs(ea.t - eb.t) > double(kCheckBvhDistanceTolerance) * 0.1 * std::max(ea.t, eb.t)) {
    if ((ea.t < eb.t ? va : vb) == Verdict::Borderline) return Outcome::Unresolved;
    return ea.t < eb.t ? Outcome::BvhFault : Outcome::EmbreeFault;
  }
  return std::abs(double(a.t) - ea.t) > std::abs(double(b.t) - eb.t) ? Outcome::EmbreeFault : Outcome::BvhFault;
}

Outcome compare(const WorldGeometry& g, const Ray& r, bool ha, const Hit& a, bool hb, const Hit& b) {
  if (ha == hb && (!ha || distances_agree(r, a.t, b.t)))
    return ha && (a.shape != b.shape || a.prim != b.prim) ? Outcome::Tie : Outcome::Agree;
  return referee(g, r, ha, a, hb, b);
}

// Occlusion answers carry no primitive: the accelerator that reported a blocker names it through intersect().
Outcome compare_occlusion(const WorldGeometry& g, const Ray& r, const Accelerator& embree, const Accelerator& bvh,
                          bool oe, bool ob) {
  if (oe == ob) return Outcome::Agree;
  const Accelerator& blocked = oe ? embree : bvh;
  const Outcome blame_blocked = oe ? Outcome::EmbreeFault : Outcome::BvhFault;
  const Outcome blame_other = oe ? Outcome::BvhFault : Outcome::EmbreeFault;
  Hit h;
  if (!blocked.intersect(r, h)) return blame_blocked;  // occluded() and intersect() contradict each other
  const Verdict v = judge(exact_hit_with_alpha(g, r, h.shape, h.prim));
  return v == Verdict::Borderline ? Outcome::Unresolved : v == Verdict::Real ? blame_other : blame_blocked;
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

std::string verdict(Outcome o) {
  return o == Outcome::EmbreeFault ? " (referee: Embree is wrong)"
         : o == Outcome::BvhFault  ? " (referee: the BVH is wrong)"
                                   : " (referee: unresolved)";
}

void count(CheckBvhKind& k, Outcome o) {
  if (o == Outcome::None) return;
  ++k.rays;
  k.disagreements += is_disagreement(o);
  k.edge_ties += o == Outcome::Tie;
  k.embree_faults += o == Outcome::EmbreeFault;
  k.bvh_faults += o == Outcome::BvhFault;
  k.unresolved += o == Outcome::Unresolved;
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
  s += "  \"embree_faults\": " + kinds_json(&CheckBvhKind::embree_faults, *this) + ",\n";
  s += "  \"bvh_faults\": " + kinds_json(&CheckBvhKind::bvh_faults, *this) + ",\n";
  s += "  \"unresolved\": " + kinds_json(&CheckBvhKind::unresolved, *this) + ",\n";
  s += "  \"max_disagreement_rate\": " + num(kCheckBvhMaxDisagreementRate) + ",\n";
  s += "  \"distance_tolerance\": " + num(kCheckBvhDistanceTolerance) + ",\n";
  s += "  \"hit_point_ulps\": " + num(kCheckBvhHitPointUlps) + ",\n";
  s += "  \"bvh\": {\"sah_cost\": " + num(bvh.sah_cost) + ", \"nodes\": " + std::to_string(bvh.nodes) +
       ", \"leaves\": " + std::to_string(bvh.leaves) + ", \"max_depth\": " + std::to_string(bvh.max_depth) +
       ", \"primitives\": " + std::to_string(bvh.primitives) + ", \"leaf_size_histogram\": [" + hist + "]},\n";
  s += "  \"build_seconds\": {\"embree\": " + num(embree_stats.build_seconds) +
       ", \"bvh\": " + num(bvh_stats.build_seconds) + "},\n";
  s += "  \"bytes\": {\"embree\": " + std::to_string(embree_stats.bytes) +
       ", \"bvh\": " + std::to_string(bvh_stats.bytes) + "},\n";
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
    out.camera = compare(geometry, cam, he, ea, hb, ba);
    if (is_disagreement(out.camera)) notes[i] = describe("camera", i, cam, he, ea, hb, ba) + verdict(out.camera);
    if (!he) return;
    const float len = length(ea.ng);
    if (!(len > 0.0f) || !std::isfinite(len)) return;  // degenerate triangle: no direction to leave in
    const Vec3f ng = ea.ng / len;
    const SurfacePoint sp = surface_point(geometry, cam, ea);
    const Vec3f p = sp.p;

    const Frame frame(face_forward(ng, -cam.d));
    const Ray bounce = spawn_ray(p, ng, frame.to_world(sample_cosine_hemisphere(rng.next_2d())), cam.time, sp.extent);
    Hit eb, bb;
    const bool he2 = embree.intersect(bounce, eb), hb2 = bvh.intersect(bounce, bb);
    out.bounce = compare(geometry, bounce, he2, eb, hb2, bb);
    if (is_disagreement(out.bounce) && notes[i].empty())
      notes[i] = describe("bounce", i, bounce, he2, eb, hb2, bb) + verdict(out.bounce);

    const Vec3f u(rng.next_float(), rng.next_float(), rng.next_float());
    const Vec3f target = scene.lo + scene.diagonal() * u;
    const Ray shadow = spawn_ray_to(p, ng, target, cam.time, sp.extent);
    const bool oe = embree.occluded(shadow), ob = bvh.occluded(shadow);
    out.shadow = compare_occlusion(geometry, shadow, embree, bvh, oe, ob);
    if (oe != ob && notes[i].empty()) {
      Hit a, b;
      a.t = b.t = oe ? 0.0f : kInfinity;
      notes[i] = describe("shadow", i, shadow, oe, a, ob, b) + verdict(out.shadow);
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
  r.passed = double(r.total_bvh_suspect()) <= kCheckBvhMaxDisagreementRate * double(r.total_rays());
  return r;
}

}  // namespace kiln
