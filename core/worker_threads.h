#pragma once
// The process-exit rule for TBB's worker threads, shared by kiln's main and the test executables' main.
#include <oneapi/tbb/global_control.h>

#include <new>

namespace kiln {

// Joins TBB's worker threads when it goes out of scope (construct it first thing in main). Left to TBB's own
// exit-time shutdown, a worker can still be tearing itself down while the process's exit handlers run;
// LeakSanitizer's exit check then reads a half-destroyed thread and crashes ("Tracer caught signal 11": exit 1 after
// a correct render, or after every test passed).
struct JoinWorkerThreadsOnReturn {
  oneapi::tbb::task_scheduler_handle scheduler{oneapi::tbb::attach{}};
  JoinWorkerThreadsOnReturn() = default;
  JoinWorkerThreadsOnReturn(const JoinWorkerThreadsOnReturn&) = delete;
  JoinWorkerThreadsOnReturn& operator=(const JoinWorkerThreadsOnReturn&) = delete;
  ~JoinWorkerThreadsOnReturn() { (void)oneapi::tbb::finalize(scheduler, std::nothrow); }
};

}  // namespace kiln
