#include "renderer/world/ray_query.h"

#include <chrono>
#include <thread>

namespace kiln {
namespace {

// How long the TSC is compared against the steady clock.
constexpr auto kTscCalibration = std::chrono::milliseconds(20);

}  // namespace

double tsc_frequency() {
  static const double f = [] {
    const auto t0 = std::chrono::steady_clock::now();
    const uint64_t c0 = __rdtsc();
    std::this_thread::sleep_for(kTscCalibration);
    const uint64_t c1 = __rdtsc();
    return double(c1 - c0) / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }();
  return f;
}

}  // namespace kiln
