// Wall-clock timing for the stage statistics (solver setup, rasterization, arrangement, frame
// phases, command totals). It lives in diffusion/, the lowest stage that times anything, so that
// every stage above uses the same clock and units.
#pragma once

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

}  // namespace wisp::diffusion
