// ProgressBar: see progress.hpp.
#include "apps/render/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>

namespace wisp::render {

ProgressBar::ProgressBar(std::string label, int total, std::FILE* out)
    : label_(std::move(label)),
      total_(std::max(total, 1)),
      out_(out),
      tty_(isatty(fileno(out)) != 0),
      start_(diffusion::Clock::now()),
      last_print_(start_) {}

void ProgressBar::update(int done) {
  done_ = std::clamp(done, 0, total_);
  const auto now = diffusion::Clock::now();
  const double since = std::chrono::duration<double>(now - last_print_).count();
  // Redraw at 10 Hz on a terminal; a plain line every 5 s elsewhere.
  if (since < (tty_ ? 0.1 : 5.0) && done_ < total_) return;
  last_print_ = now;
  print(false);
}

void ProgressBar::finish() {
  if (finished_) return;
  finished_ = true;
  print(true);
}

void ProgressBar::print(bool final_line) {
  const double elapsed = diffusion::seconds_since(start_);
  const double rate = elapsed > 0 ? done_ / elapsed : 0.0;
  const double eta = rate > 0 ? (total_ - done_) / rate : 0.0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = kWidth * done_ / total_;
    std::string bar(filled, '#');
    bar.resize(kWidth, '.');
    std::fprintf(out_, "\r%s [%s] %d/%d  %.1f/s  ETA %.0fs ", label_.c_str(), bar.c_str(), done_,
                 total_, rate, eta);
    if (final_line) std::fprintf(out_, "\n");
  } else if (final_line) {
    std::fprintf(out_, "%s: %d/%d done in %.1fs (%.1f/s)\n", label_.c_str(), done_, total_, elapsed,
                 rate);
  } else {
    std::fprintf(out_, "%s: %d/%d  %.1f/s  ETA %.0fs\n", label_.c_str(), done_, total_, rate, eta);
  }
  std::fflush(out_);
}

}  // namespace wisp::render
