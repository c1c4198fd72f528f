// The test executables' main: gtest's, plus the exit rule kiln's own main follows (core/worker_threads.h). Tests that
// render in-process leave TBB's workers running; joined here, LeakSanitizer's exit check never meets one mid-exit.
#include <gtest/gtest.h>

#include "core/worker_threads.h"

int main(int argc, char** argv) {
  const kiln::JoinWorkerThreadsOnReturn join_workers;
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
