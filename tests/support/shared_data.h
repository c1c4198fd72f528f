// Tests that read ../shared (the course scenes, configs and the killeroo) find it through KILN_SHARED_DIR. A
// developer without it gets a skip that says so; a build configured with KILN_REQUIRE_SHARED=ON (CI) turns the
// skip into a failure, so the suite cannot pass by skipping.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>

#ifndef KILN_SHARED_REQUIRED
#define KILN_SHARED_REQUIRED 0
#endif

// Skips (or, with KILN_REQUIRE_SHARED=ON, fails) the current test when `path` does not exist.
#define KILN_NEED_SHARED_PATH(path)                                                                      \
  do {                                                                                                   \
    if (!std::filesystem::exists(path)) {                                                                \
      if (KILN_SHARED_REQUIRED) GTEST_FAIL() << (path) << " not found (KILN_REQUIRE_SHARED=ON)";        \
      GTEST_SKIP() << (path) << " not found: configure with -DKILN_SHARED_DIR=<folder with scenes/>"; \
    }                                                                                                    \
  } while (0)
