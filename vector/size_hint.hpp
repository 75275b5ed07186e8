// The size a growing array reached in the last call on this thread. A frame's arrangement grows
// arrays of megabytes element by element; grown by doubling, each one is copied a dozen times and
// its new storage faulted in each time (about 0.3-4.6 ms a MB on the VMs we measure on). Frames
// that follow one another are alike, so the next call reserves a little more than the last one
// reached, at once. Used as `thread_local SizeHint`: the hint is per thread, the arrays are not
// kept (their memory is freed as before).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace wisp::vector {

struct SizeHint {
  std::size_t last = 0;

  // Reserves an eighth more than the last size, or `at_least` if that is more: one allocation.
  template <class T>
  void reserve(std::vector<T>& v, std::size_t at_least = 0) const {
    v.reserve(std::max(at_least, last + last / 8));
  }
  template <class T>
  void remember(const std::vector<T>& v) {
    last = v.size();
  }
};

}  // namespace wisp::vector
