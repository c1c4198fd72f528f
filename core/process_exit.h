#pragma once
// The process-exit rule, shared by kiln's main and the test executables' main: construct ExitCleanlyOnReturn first
// thing in main.
#include <oneapi/tbb/global_control.h>

#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define KILN_LEAK_CHECK_ON_RETURN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define KILN_LEAK_CHECK_ON_RETURN 1
#endif
#endif
#ifdef KILN_LEAK_CHECK_ON_RETURN
#include <sanitizer/lsan_interface.h>
#endif

namespace kiln {

// When main returns: joins TBB's worker threads, then (under AddressSanitizer) runs LeakSanitizer's check at once
// instead of at exit. Both keep the check away from threads that are still tearing themselves down, which crashes it
// ("Tracer caught signal 11": exit 1 after a correct render, or after every test passed):
// - TBB's workers, left to TBB's exit-time shutdown, can still be ending while the exit handlers run;
// - the image plugin's libraries (OpenImageIO → OpenVDB → log4cplus) start a thread pool when they load and stop it
//   during static destruction, just before the at-exit check. At main's return those threads are still parked.
struct ExitCleanlyOnReturn {
  oneapi::tbb::task_scheduler_handle scheduler{oneapi::tbb::attach{}};
  ExitCleanlyOnReturn() = default;
  ExitCleanlyOnReturn(const ExitCleanlyOnReturn&) = delete;
  ExitCleanlyOnReturn& operator=(const ExitCleanlyOnReturn&) = delete;
  ~ExitCleanlyOnReturn() {
    (void)oneapi::tbb::finalize(scheduler, std::nothrow);
#ifdef KILN_LEAK_CHECK_ON_RETURN
    __lsan_do_leak_check();  // later calls, the at-exit one included, do nothing
#endif
  }
};

}  // namespace kiln
