// ThreadSanitizer <-> oneTBB glue for the TSan CI stage (.ci/tsan.sh builds it and loads it into the tests with
// LD_PRELOAD, and names it as libtbb's ITT collector).
//
// Debian's libtbb (and Embree, which runs its BVH build on TBB) is not built with -fsanitize=thread, so TSan does
// not see the synchronisation inside the task scheduler: everything written before tbb::parallel_for and read in a
// task, or written in a task and read after the loop, is reported as a race, and a real race in our code would
// drown in hundreds of false reports. This library adds, as TSan happens-before edges, exactly the orderings the
// scheduler guarantees, at its exported entry points:
//
//   spawn        r1::spawn(task)  (any caller, Embree included)     -> release(&task)
//   execute      libtbb's ITT hook __itt_sync_acquired(&task)        -> acquire(&task)
//                (oneTBB annotates its dispatcher for race detectors such as Intel Inspector; libtbb loads this
//                library as the ITT collector named by INTEL_LIBITTNOTIFY64, for INTEL_ITTNOTIFY_GROUPS=sync)
//   wait         r1::execute_and_wait / r1::wait returning           -> acquire-load of the wait_context's
//                reference count, which every finishing task decremented with an (instrumented, in our code)
//                atomic RMW: the waiter is ordered after all the tasks it waited for
//   task memory  r1::deallocate(p) / r1::allocate returning p        -> release(p) / acquire(p): TBB's small-object
//                pool hands a block freed by one thread to another, like malloc/free, which TSan already orders
//
// Nothing here hides an access or a report: two tasks writing the same pixel, or a read of a result before the loop
// that produces it has been waited for, are still races (checked: two concurrent render_samples into one Film are
// reported at renderer/render/render.cpp's pixel sums). Races inside Embree/libstdc++ themselves are not ours to
// see (TSAN_OPTIONS ignore_noninstrumented_modules=1 in .ci/tsan.sh).
//
// With KILN_TSAN_GLUE_LOG=<file>, every process appends "<pid> <executable> <n>" at exit: n threads passed through
// libtbb's acquire hook (it runs on the thread about to execute a task), so the stage can check that the tasks
// really ran on 2+ threads.
//
// Built without -fsanitize: the TSan entry points are weak, so a preloaded process without the TSan runtime (the
// /bin/sh that std::system starts) loads this library and the hooks do nothing.
#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

extern "C" {
void __tsan_acquire(void* addr) __attribute__((weak));
void __tsan_release(void* addr) __attribute__((weak));
long __tsan_atomic64_load(const volatile long* addr, int memory_order) __attribute__((weak));
}

namespace {

constexpr int kTsanMemoryOrderAcquire = 2;  // __tsan_memory_order_acquire

void acquire(void* p) {
  if (__tsan_acquire && p) __tsan_acquire(p);
}
void release(void* p) {
  if (__tsan_release && p) __tsan_release(p);
}

std::atomic<int> g_task_threads{0};
thread_local bool t_counted = false;

void count_task_thread() {
  if (!t_counted) {
    t_counted = true;
    g_task_threads.fetch_add(1, std::memory_order_relaxed);
  }
}

__attribute__((destructor)) void log_task_threads() {
  const char* path = std::getenv("KILN_TSAN_GLUE_LOG");
  if (!path || !*path || g_task_threads.load() == 0) return;
  char exe[4096] = {};
  if (readlink("/proc/self/exe", exe, sizeof exe - 1) < 0) std::strcpy(exe, "?");
  if (FILE* f = std::fopen(path, "a")) {
    std::fprintf(f, "%d %s %d\n", int(getpid()), exe, g_task_threads.load());
    std::fclose(f);
  }
}

// oneapi/tbb/detail/_task.h (oneTBB 2021): class wait_context { std::uint64_t m_version_and_traits{1};
// std::atomic<std::uint64_t> m_ref_count; ... }. The layout is checked on every use: a TBB update that changes
// it stops the stage with a message instead of silently losing the edge.
constexpr std::size_t kWaitContextRefCountOffset = 8;
constexpr std::uint64_t kWaitContextVersion = 1;

void acquire_wait_context(void* wait_ctx) {
  if (!__tsan_atomic64_load) return;
  std::uint64_t version;
  std::memcpy(&version, wait_ctx, sizeof version);
  if (version != kWaitContextVersion) {
    std::fprintf(stderr, "tsan_tbb_glue: unexpected tbb::detail::d1::wait_context layout (version %llu); update "
                         ".ci/tsan_tbb_glue.cpp for this oneTBB\n", static_cast<unsigned long long>(version));
    std::abort();
  }
  __tsan_atomic64_load(reinterpret_cast<const volatile long*>(static_cast<char*>(wait_ctx) + kWaitContextRefCountOffset),
                       kTsanMemoryOrderAcquire);
}

template <typename F>
F real_function(const char* mangled) {
  void* f = dlsym(RTLD_NEXT, mangled);
  if (!f) {
    std::fprintf(stderr, "tsan_tbb_glue: %s not found in libtbb\n", mangled);
    std::abort();
  }
  return reinterpret_cast<F>(f);
}

}  // namespace

#define KILN_EXPORT __attribute__((visibility("default")))

// ITT collector interface (version 1: libtbb looks each hook up by name; a missing one stays a no-op).
extern "C" {
KILN_EXPORT int __itt_api_version(void) { return 1; }
KILN_EXPORT void __itt_sync_acquired(void* addr) {
  count_task_thread();
  acquire(addr);
}
KILN_EXPORT void __itt_sync_releasing(void* addr) { release(addr); }
KILN_EXPORT void __itt_sync_prepare(void*) {}
KILN_EXPORT void __itt_sync_cancel(void*) {}
KILN_EXPORT void __itt_sync_destroy(void*) {}
KILN_EXPORT void __itt_sync_create(void*, const char*, const char*, int) {}
KILN_EXPORT void __itt_sync_rename(void*, const char*) {}
}

// libtbb's exported scheduler entry points (oneapi/tbb/detail/_task.h, _small_object_pool.h), wrapped; the real
// functions are found with RTLD_NEXT by their mangled names.
namespace tbb::detail {
namespace d1 {
class task;
class task_group_context;
class wait_context;
class small_object_pool;
struct execution_data;
}  // namespace d1
namespace r1 {

KILN_EXPORT void spawn(d1::task& t, d1::task_group_context& ctx) {
  using Fn = void (*)(d1::task&, d1::task_group_context&);
  static const Fn real = real_function<Fn>("_ZN3tbb6detail2r15spawnERNS0_2d14taskERNS2_18task_group_contextE");
  release(&t);
  real(t, ctx);
}

KILN_EXPORT void spawn(d1::task& t, d1::task_group_context& ctx, unsigned short slot) {
  using Fn = void (*)(d1::task&, d1::task_group_context&, unsigned short);
  static const Fn real = real_function<Fn>("_ZN3tbb6detail2r15spawnERNS0_2d14taskERNS2_18task_group_contextEt");
  release(&t);
  real(t, ctx, slot);
}

KILN_EXPORT void execute_and_wait(d1::task& t, d1::task_group_context& t_ctx, d1::wait_context& wait_ctx,
                                  d1::task_group_context& w_ctx) {
  using Fn = void (*)(d1::task&, d1::task_group_context&, d1::wait_context&, d1::task_group_context&);
  static const Fn real = real_function<Fn>(
      "_ZN3tbb6detail2r116execute_and_waitERNS0_2d14taskERNS2_18task_group_contextERNS2_12wait_contextES6_");
  release(&t);
  real(t, t_ctx, wait_ctx, w_ctx);
  acquire_wait_context(&wait_ctx);
}

KILN_EXPORT void wait(d1::wait_context& wait_ctx, d1::task_group_context& ctx) {
  using Fn = void (*)(d1::wait_context&, d1::task_group_context&);
  static const Fn real = real_function<Fn>("_ZN3tbb6detail2r14waitERNS0_2d112wait_contextERNS2_18task_group_contextE");
  real(wait_ctx, ctx);
  acquire_wait_context(&wait_ctx);
}

KILN_EXPORT void* allocate(d1::small_object_pool*& pool, std::size_t bytes, const d1::execution_data& ed) {
  using Fn = void* (*)(d1::small_object_pool*&, std::size_t, const d1::execution_data&);
  static const Fn real =
      real_function<Fn>("_ZN3tbb6detail2r18allocateERPNS0_2d117small_object_poolEmRKNS2_14execution_dataE");
  void* p = real(pool, bytes, ed);
  acquire(p);
  return p;
}

KILN_EXPORT void* allocate(d1::small_object_pool*& pool, std::size_t bytes) {
  using Fn = void* (*)(d1::small_object_pool*&, std::size_t);
  static const Fn real = real_function<Fn>("_ZN3tbb6detail2r18allocateERPNS0_2d117small_object_poolEm");
  void* p = real(pool, bytes);
  acquire(p);
  return p;
}

KILN_EXPORT void deallocate(d1::small_object_pool& pool, void* p, std::size_t bytes, const d1::execution_data& ed) {
  using Fn = void (*)(d1::small_object_pool&, void*, std::size_t, const d1::execution_data&);
  static const Fn real =
      real_function<Fn>("_ZN3tbb6detail2r110deallocateERNS0_2d117small_object_poolEPvmRKNS2_14execution_dataE");
  release(p);
  real(pool, p, bytes, ed);
}

KILN_EXPORT void deallocate(d1::small_object_pool& pool, void* p, std::size_t bytes) {
  using Fn = void (*)(d1::small_object_pool&, void*, std::size_t);
  static const Fn real = real_function<Fn>("_ZN3tbb6detail2r110deallocateERNS0_2d117small_object_poolEPvm");
  release(p);
  real(pool, p, bytes);
}

}  // namespace r1
}  // namespace tbb::detail
