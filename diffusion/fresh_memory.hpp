// Fresh memory, faulted in by every worker thread at once. A process's first use of a large array
// is a page fault per page, in which the kernel zeroes the page (and, on a virtual machine whose
// host has not backed that memory yet, the host faults it in too): 0.06-2.6 ms a MB on the VMs
// we measure on, paid by the thread that writes the page first. `wisp diffuse` of a 1024^2
// drawing takes about 100 MB of fresh arrays (the problem, the solver's levels, the answer), and
// filling each with std::vector::assign put all of those faults on one thread. Here the pages of
// new storage are touched in parallel before the (serial) assignment, so the faults are shared
// by the cores; the values are those of a plain assign. Storage the vector already has is kept
// as it is: reused arrays (a renderer's solver workspace) cost nothing more.
//
// The solver's own arrays go further (UninitializedVector): a vector that does not
// value-initialise what it grows by, so that assign_touched fills it by the worker threads
// together, in the same pass that faults its pages in. A std::vector's assign is one thread's
// stores over the whole array, about a millisecond for a 12 MB plane, and a 1024^2 drawing's
// solver sets up some 80 MB of them.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
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

// std::allocator, except that an element made without arguments (a vector's resize) is
// default-initialised: for float and bytes, not written at. Every array that uses it is written
// whole (assign_touched below, or the pass that computes it) before it is read. Its storage
// starts on a 64-byte cache line, so that rows laid out on whole lines (the solver's levels) are
// read a line per sixteen floats.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  static constexpr std::align_val_t kAlignment{64};
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, kAlignment); }
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using UninitializedVector = std::vector<T, UninitializedAllocator<T>>;

// v.assign(n, value), the stores shared by the worker threads in tasks of 2 MiB (a transparent
// huge page), which also fault in any new storage. The contents are a plain assign's.
template <class T>
void assign_touched(UninitializedVector<T>& v, std::size_t n, const T& value) {
  if (v.capacity() < n) {
    UninitializedVector<T>().swap(v);  // nothing to keep: no copy into the new storage
    v.reserve(n);
  }
  v.resize(n);  // no stores (UninitializedAllocator)
  constexpr std::size_t kPerTask = (std::size_t(2) << 20) / sizeof(T);
  T* data = v.data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kPerTask),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::fill(data + r.begin(), data + r.end(), value);
                    });
}

}  // namespace wisp::diffusion
