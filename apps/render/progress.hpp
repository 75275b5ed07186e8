// A progress bar for long jobs (simulation, rendering): items done, items per second and ETA.
// On a terminal it redraws one line in place; otherwise (logs, CI) it prints a plain line at most
// every few seconds, so piped output stays readable.
#pragma once

#include <cstdio>
#include <string>

#include "diffusion/timer.hpp"

namespace wisp::render {

class ProgressBar {
 public:
  ProgressBar(std::string label, int total, std::FILE* out = stderr);
  // Reports that `done` of `total` items are complete. Cheap to call often.
  void update(int done);
  // Prints the final line (total time) and ends the bar.
  void finish();

 private:
  std::string label_;
  int total_;
  std::FILE* out_;
  bool tty_;
  diffusion::Clock::time_point start_, last_print_;
  int done_ = 0;
  bool finished_ = false;
  void print(bool final_line);
};

}  // namespace wisp::render
