// Fresh memory, faulted in by every worker thread at once. A process's first use of a large array
// is a page fault per page, in which the kernel zeroes the page (and, on a virtual machine whose
// host has not backed that memory yet, the host faults it in too): 0.06-2.6 ms a MB on the VMs
// we measure on, paid by the thread that writes the page first. `wisp diffuse` of a 1024^2
// drawing takes about 100 MB of fresh arrays (the problem, the solver's levels, the answer), and
// filling each with std::vector::assign put all of those faults on one thread. Here the pages of
// new storage are touched in parallel before the (serial) assignment, so the faults are shared
// by the cores; the values are those of a plain assign. Storage the vector already has is kept
// as it is: reused arrays (a renderer's solver workspace) cost nothing more.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <vector>

namespace wisp::diffusion {

// Below this size new storage is simply reserved: too few pages to share out.
constexpr std::size_t kTouchBytes = std::size_t(1) << 20;

// Makes v.capacity() at least n, keeping v's elements. New storage of kTouchBytes or more is
// allocated whole and each of its pages written once, by the worker threads together, before the
// elements move in.
template <class T>
void reserve_touched(std::vector<T>& v, std::size_t n) {
  if (v.capacity() >= n) return;
  if (n * sizeof(T) < kTouchBytes) {
    v.reserve(n);
    return;
  }
  std::vector<T> fresh;
  fresh.reserve(n);
  // The storage holds no elements yet: it is written as bytes (unsigned char may alias any
  // storage), one every 4 KiB, in tasks of 2 MiB (a transparent huge page).
  unsigned char* bytes = reinterpret_cast<unsigned char*>(fresh.data());
  constexpr std::size_t kPage = 4096, kPagesPerTask = 512;
  const std::size_t pages = (n * sizeof(T) + kPage - 1) / kPage;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pages, kPagesPerTask),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k < r.end(); ++k) bytes[k * kPage] = 0;
                    });
  fresh.insert(fresh.end(), v.begin(), v.end());
  v.swap(fresh);
}

// v.assign(n, value), with any new storage touched in parallel first (reserve_touched). The
// elements are all replaced, so none is moved into new storage.
template <class T>
void assign_touched(std::vector<T>& v, std::size_t n, const T& value) {
  if (v.capacity() < n) v.clear();
  reserve_touched(v, n);
  v.assign(n, value);
}

}  // namespace wisp::diffusion
