// The test executables' main: gtest's, plus the exit rule kiln's own main follows (core/process_exit.h). Tests that
// render in-process leave TBB's workers running, and those that read a JPEG or HDR image load the image plugin's
// libraries with their thread pool; under ASan the leak check runs at main's return, while no thread is ending.
#include <gtest/gtest.h>

#include "core/process_exit.h"

int main(int argc, char** argv) {
  const kiln::ExitCleanlyOnReturn exit_cleanly;
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
