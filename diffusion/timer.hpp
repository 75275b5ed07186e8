// Wall-clock timing for the stage statistics (solver setup, rasterization, arrangement, frame
// phases, command totals), and the calling thread's CPU time for comparisons on a loaded machine.
// It lives in diffusion/, the lowest stage that times anything, so that every stage above uses
// the same clock and units.
#pragma once

#include <time.h>

#include <chrono>

namespace wisp::diffusion {

using Clock = std::chrono::steady_clock;  // monotonic: durations never go negative

// Milliseconds elapsed since t0.
inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Seconds elapsed since t0.
inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU time of the calling thread in milliseconds (not wall time: other processes on the machine
// do not count). Differences are meaningful only on the same thread.
inline double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

}  // namespace wisp::diffusion
