// EXR output keeps every float: a 1e6 light seen directly or an accumulated 3e38 must survive a write/read round
// trip. Half floats (the EXR default in many tools) top out at 65504 and would turn these into Inf.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"

namespace kiln::test {
namespace {

// Why: values beyond half range (65504), at its edge, far below it (half denormals flush) and near the float limit
// come back bit-identical, along with an AOV layer and metadata.
TEST(StabilityExr, ValuesBeyondHalfRangeRoundTrip) {
  const float values[] = {1e6f, 3e38f, std::numeric_limits<float>::max(), 65504.0f, 65520.0f, 1e5f + 0.25f,
                          1e-30f, 6e-8f, 0.1f, 0.0f, 123456.789f, 2.5e9f};
  constexpr int kW = 4, kH = 3;
  static_assert(kW * kH * 3 >= int(std::size(values)));
  Image img(kW, kH);
  AovLayer depth{{"Z"}, std::vector<float>(size_t(kW * kH))};
  for (int i = 0; i < kW * kH; ++i) {
    Rgb& p = img.pixels()[size_t(i)];
    p.r = values[size_t(i) % std::size(values)];
    p.g = values[size_t(i + 5) % std::size(values)];
    p.b = values[size_t(i + 7) % std::size(values)];
    depth.data[size_t(i)] = values[size_t(i + 3) % std::size(values)];
  }
  const std::string path = tmp_dir("stability_exr") + "/big.exr";
  write_exr(path, img, {depth}, {{"kiln:note", "float32 round trip"}});
  const ExrFile back = read_exr(path);
  ASSERT_EQ(back.rgb.width(), kW);
  ASSERT_EQ(back.rgb.height(), kH);
  for (int i = 0; i < kW * kH; ++i)
    for (int c = 0; c < 3; ++c) {
      const float want = img.pixels()[size_t(i)][c], got = back.rgb.pixels()[size_t(i)][c];
      EXPECT_EQ(std::memcmp(&want, &got, sizeof(float)), 0) << "pixel " << i << " channel " << c << ": wrote " << want
                                                             << ", read " << got;
    }
  ASSERT_EQ(back.aovs.size(), 1u);
  EXPECT_EQ(back.aovs[0].channels, std::vector<std::string>{"Z"});
  EXPECT_EQ(back.aovs[0].data, depth.data);
  bool found = false;
  for (const auto& [k, v] : back.meta) found |= k == "kiln:note" && v == "float32 round trip";
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace kiln::test
