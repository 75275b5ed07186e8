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
// order each time: it runs twice, to count and to fill. Into `begin` and `items`, whose capacity
// is kept (a caller that keeps them across calls takes no fresh pages from the system).
template <typename T, typename Each>
void bucket_into(std::vector<int>& begin, std::vector<T>& items, int keys, const Each& each) {
  begin.assign(std::size_t(keys) + 1, 0);
  each([&](int key, const T&) { ++begin[std::size_t(key) + 1]; });
  for (int k = 0; k < keys; ++k) begin[k + 1] += begin[k];
  items.resize(std::size_t(begin[keys]));
  // begin[k + 1] is the fill position of key k, so that it ends at key k + 1's start.
  for (int k = keys; k > 0; --k) begin[k] = begin[k - 1];
  each([&](int key, const T& item) { items[std::size_t(begin[key + 1]++)] = item; });
}

template <typename T, typename Each>
Buckets<T> bucket(int keys, const Each& each) {
  Buckets<T> b;
  bucket_into(b.begin, b.items, keys, each);
  return b;
}

}  // namespace wisp::vector
