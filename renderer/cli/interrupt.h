// SIGINT / SIGTERM while a command renders set a flag that the renders poll (RenderOptions::cancel) instead of ending
// the process, so that what was rendered is still written. InterruptGuard installs the handlers and puts the previous
// ones back however the command ends, an exception included. One guard at a time.
#pragma once
#include <atomic>

namespace kiln {

class InterruptGuard {
 public:
  InterruptGuard();  // clears the flag
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  const std::atomic<bool>& flag() const;
  bool interrupted() const { return flag().load(); }

 private:
  using Handler = void (*)(int);
  Handler previous_int_, previous_term_;
};

}  // namespace kiln
