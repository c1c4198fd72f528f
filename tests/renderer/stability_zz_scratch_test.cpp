// TEMPORARY investigation (to be deleted).
#include <gtest/gtest.h>
#include "stability_util.h"
namespace kiln::test {
namespace {
int add_material(SceneDesc& s, MaterialDesc m) { m.id = int(s.materials.size() + 1); s.materials.push_back(m); return int(s.materials.size() - 1); }
int glass(SceneDesc& s, float eta) { MaterialDesc m; m.type = MaterialType::Dielectric; m.refraction_index = eta; m.has_refraction_index = true; return add_material(s, m); }
void add_sphere(SceneDesc& s, Vec3f c, float r, int material) { SphereDesc d; d.center = c; d.radius = r; d.material = material; s.spheres.push_back(d); }
TEST(Scratch, Dielectrics) {
  for (int which = 0; which < 4; ++which) for (uint64_t seed : {1, 2, 3}) {
    SceneDesc s = furnace_box(0.5f, Rgb(1.0f));
    s.cameras[0].width = s.cameras[0].height = 32;
    if (which == 0 || which == 3) add_sphere(s, {-0.45f, 0.3f, -0.5f}, 0.3f, glass(s, 10.0f));
    if (which == 1 || which == 3) add_sphere(s, {0.35f, 0.35f, -0.6f}, 0.3f, glass(s, 1.0001f));
    if (which == 2 || which == 3) s.meshes.push_back(box_mesh("cube", {-0.2f, -0.8f, -0.7f}, {0.4f, -0.2f, -0.1f}, glass(s, 1.5f)));
    const auto w = build_world(s, {});
    IntegratorSettings st; st.max_depth = -1; st.russian_roulette = true; st.features = w->features;
    const Rendered r = render_film(*w, s.cameras[0], st, 64, seed);
    const MeanEstimate m = film_mean(r.film);
    auto z = block_z(r.film, 8, 2.0);
    std::printf("which %d seed %lu mean %.5f se %.5f nan %lu blocks:", which, (unsigned long)seed, m.mean, m.se, (unsigned long)r.stats.rays.nan_samples);
    for (double v : z) std::printf(" %5.1f", v);
    std::printf("\n");
  }
}
}  // namespace
}  // namespace kiln::test
