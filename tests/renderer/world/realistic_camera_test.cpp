// The realistic camera's lens system (renderer/world/lens_system.h) on a lens whose optics have closed forms: a
// biconvex singlet (radii +-50 mm, 5 mm of glass of index 1.5, 40 mm across) with a 24 mm aperture stop 3 mm
// behind it.
//   * focused at infinity, the film sits at the singlet's back focal distance (thick-lens formula) minus 3 mm;
//   * focused at 1 m, rays from the film centre through the stop meet again on the axis 1 m in front of the film;
//   * the exit pupil is the stop itself, so the mean weight of the film centre's rays is the projected solid angle
//     of a disk of radius r at distance d, pi r^2 / (r^2 + d^2);
//   * every ray that passes the lens from a film ring lies inside that ring's exit-pupil bounds;
//   * a lens file row without four values is an error naming the file and the line.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/rng.h"
#include "renderer/world/lens_system.h"
#include "scenes/pbrt/camera.h"

namespace kiln {
namespace {

constexpr const char* kSinglet = R"(# biconvex singlet, stop behind it
# radius  thickness  eta  aperture
50    5   1.5  40
-50   3   1    40
0     45  0    24
)";
constexpr float kStopRadius = 0.012f;
// Rays per exit-pupil ring: pbrt's 2^20 take seconds; 2^14 keep the test fast (the bounds are then padded more).
constexpr int kPupilSamples = 1 << 14;

LensSystem singlet(float focus_distance) {
  LensSystemDesc d;
  d.file = "singlet.dat";
  d.interfaces = parse_lens_file(kSinglet, d.file);
  d.focus_distance = focus_distance;
  return LensSystem(d, 100, 100, "test", kPupilSamples);
}

// Thick lens: 1/f = (n - 1) (1/R1 - 1/R2 + (n - 1) t / (n R1 R2)); back focal distance f (1 - (n - 1) t / (n R1)).
TEST(RealisticCamera, FocusedAtInfinityTheFilmIsAtTheBackFocalPoint) {
  const double n = 1.5, r1 = 50, r2 = -50, t = 5;
  const double f = 1.0 / ((n - 1) * (1 / r1 - 1 / r2 + (n - 1) * t / (n * r1 * r2)));
  const double bfd_mm = f * (1 - (n - 1) * t / (n * r1));
  const LensSystem lens = singlet(1e6f);
  EXPECT_NEAR(lens.rear_z(), (bfd_mm - 3.0) * 1e-3, 2e-3 * (bfd_mm - 3.0) * 1e-3);
  EXPECT_NEAR(lens.front_z(), lens.rear_z() + 0.008f, 1e-6f);
}

// Rays from the film centre through the stop cross the axis again near the focus distance; spherical aberration
// pulls the crossing in by a h^2 for a ray through height h of the stop, so the paraxial limit, z(0) =
// (4 z(h) - z(2h)) / 3, is where the thick-lens focus put it.
TEST(RealisticCamera, RaysFromTheFilmCentreMeetAtTheFocusDistance) {
  const LensSystem lens = singlet(1.0f);
  const auto crossing = [&](float h) {
    const Vec3f film(0, 0, 0), stop(h, 0, lens.rear_z());
    Ray out;
    EXPECT_GT(lens.trace_from_film(Ray{film, stop - film}, &out), 0.0f) << "h " << h;
    const double t = -double(out.o.x) / out.d.x;
    return out.o.z + out.d.z * t;
  };
  const double z1 = crossing(0.0003f), z2 = crossing(0.0006f);
  EXPECT_LT(z2, z1) << "a positive singlet's marginal rays focus short";
  EXPECT_NEAR((4.0 * z1 - z2) / 3.0, 1.0, 2e-3);
}

// E[weight] = integral over the pupil of cos^4 / d^2 dA = pi r^2 / (r^2 + d^2) for the film centre.
TEST(RealisticCamera, FilmCentreWeightIsTheStopsProjectedSolidAngle) {
  const LensSystem lens = singlet(2.0f);
  const double d = lens.rear_z(), r = kStopRadius;
  const double expected = kPi * r * r / (r * r + d * d);
  Rng rng(5, 0);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    Ray ray;
    const double w = lens.generate({0.5f, 0.5f}, rng.next_2d(), ray);
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, expected, 4.0 * sigma + 1e-3 * expected) << "sigma " << sigma;
}

// The bounds pbrt-v4 finds for a ring hold every rear-element point a ray from that ring passes through.
TEST(RealisticCamera, ExitPupilBoundsHoldEveryPassingRay) {
  const LensSystem lens = singlet(2.0f);
  ASSERT_EQ(lens.exit_pupil().size(), size_t(kExitPupilRings));
  Rng rng(9, 0);
  const float half_diagonal = 0.5f * lens.film_diagonal(), rear = 1.5f * kStopRadius;
  for (int ring : {0, 17, 40, kExitPupilRings - 1}) {
    const PupilBounds& b = lens.exit_pupil()[size_t(ring)];
    int passed = 0;
    for (int i = 0; i < 20000; ++i) {
      const float x = half_diagonal * (float(ring) + rng.next_float()) / kExitPupilRings;
      const Vec3f film(x, 0, 0), p(rear * (2 * rng.next_float() - 1), rear * (2 * rng.next_float() - 1), lens.rear_z());
      if (!lens.trace_from_film(Ray{film, p - film}, nullptr)) continue;
      ++passed;
      ASSERT_TRUE(p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y)
          << "ring " << ring << " point " << p.x << " " << p.y;
    }
    EXPECT_GT(passed, 0) << "ring " << ring;
  }
}

TEST(RealisticCamera, LensFileRowsNeedFourValues) {
  try {
    parse_lens_file("# r t eta ap\n50 5 1.5 20\n-50 3 1\n", "lenses/bad.dat");
    FAIL() << "a three-value row was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("lenses/bad.dat: line 3"), std::string::npos) << m;
    EXPECT_NE(m.find("has 3 values"), std::string::npos) << m;
  }
  EXPECT_THROW(parse_lens_file("# nothing\n", "empty.dat"), Error);
  EXPECT_THROW(parse_lens_file("50 5 1.5 abc\n", "word.dat"), Error);
}

}  // namespace
}  // namespace kiln
