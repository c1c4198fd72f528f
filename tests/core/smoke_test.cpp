#include <gtest/gtest.h>
#include "core/transform.h"
TEST(Smoke, Identity) { EXPECT_TRUE(kiln::Transform().is_identity()); }
