// Items grouped by an integer key in one array (a stable counting sort), the layout of the
// index-based structures in vector/ and apps/render/: key k's items are items[begin[k]] to
// items[begin[k + 1]], in the order they were put.
#pragma once

#include <cstddef>
#include <vector>

namespace wisp::vector {

template <typename T>
struct Buckets {
  std::vector<int> begin;
  std::vector<T> items;
};

// `each(put)` calls put(key, item) for every item, key in [0, keys), the same ones in the same
// order each time: it runs twice, to count and to fill.
template <typename T, typename Each>
Buckets<T> bucket(int keys, const Each& each) {
  Buckets<T> b;
  b.begin.assign(std::size_t(keys) + 1, 0);
  each([&](int key, const T&) { ++b.begin[std::size_t(key) + 1]; });
  for (int k = 0; k < keys; ++k) b.begin[k + 1] += b.begin[k];
  b.items.resize(std::size_t(b.begin[keys]));
  std::vector<int> fill(b.begin.begin(), b.begin.end() - 1);
  each([&](int key, const T& item) { b.items[std::size_t(fill[key]++)] = item; });
  return b;
}

}  // namespace wisp::vector
