// Fresh memory faulted in by the worker threads (diffusion/fresh_memory.hpp): the contents are a
// plain assign's, the elements a vector had are kept when it grows, and storage it already has is
// reused, not replaced.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <numeric>
#include <vector>

#include "diffusion/fresh_memory.hpp"

using namespace wisp::diffusion;

TEST_CASE("assign_touched fills like assign, small and large", "[fresh_memory]") {
  // 1 KB stays below the touch threshold; 12 MB and an odd size above it are touched by tasks.
  for (std::size_t n : {std::size_t(256), std::size_t(3) << 20, (std::size_t(3) << 20) + 7}) {
    std::vector<float> v;
    assign_touched(v, n, 0.25f);
    REQUIRE(v.size() == n);
    CHECK(std::all_of(v.begin(), v.end(), [](float x) { return x == 0.25f; }));
    std::vector<std::uint8_t> bytes = {9, 9};
    assign_touched(bytes, n, std::uint8_t(3));
    REQUIRE(bytes.size() == n);
    CHECK(std::all_of(bytes.begin(), bytes.end(), [](std::uint8_t x) { return x == 3; }));
  }
}

TEST_CASE("reserve_touched keeps the elements when it grows", "[fresh_memory]") {
  std::vector<int> v(1000);
  std::iota(v.begin(), v.end(), 1);
  const std::size_t n = std::size_t(1) << 20;  // 4 MB of ints: touched
  reserve_touched(v, n);
  CHECK(v.capacity() >= n);
  REQUIRE(v.size() == 1000);
  for (int i = 0; i < 1000; ++i) REQUIRE(v[i] == i + 1);
}

TEST_CASE("storage a vector already has is reused", "[fresh_memory]") {
  std::vector<float> v;
  assign_touched(v, std::size_t(1) << 20, 1.0f);
  const float* storage = v.data();
  assign_touched(v, std::size_t(1) << 19, 2.0f);  // smaller: same storage, new values
  CHECK(v.data() == storage);
  CHECK(v.size() == std::size_t(1) << 19);
  CHECK(v.front() == 2.0f);
  CHECK(v.back() == 2.0f);
  reserve_touched(v, std::size_t(1) << 20);
  CHECK(v.data() == storage);
}

TEST_CASE("assign_touched fills an UninitializedVector whole, in every size it takes",
          "[fresh_memory]") {
  // The solver's arrays grow unwritten (UninitializedAllocator): every element they hold is the
  // fill's. Sizes below one task, across several tasks and not a multiple of one; storage kept
  // (smaller, then as large again) and replaced (larger), each time over other values.
  UninitializedVector<float> v;
  float value = 0.5f;
  for (std::size_t n : {std::size_t(100), (std::size_t(3) << 20) + 7, std::size_t(1) << 20,
                        (std::size_t(3) << 20) + 7, std::size_t(5) << 20}) {
    const float* before = v.data();
    const bool fits = v.capacity() >= n;
    assign_touched(v, n, value);
    REQUIRE(v.size() == n);
    CHECK(std::all_of(v.begin(), v.end(), [&](float x) { return x == value; }));
    if (fits) CHECK(v.data() == before);  // storage it has is reused
    value += 1.0f;
  }
  UninitializedVector<std::uint8_t> bytes;
  assign_touched(bytes, std::size_t(3) << 20, std::uint8_t(7));
  assign_touched(bytes, (std::size_t(3) << 20) - 1, std::uint8_t(0));
  CHECK(std::all_of(bytes.begin(), bytes.end(), [](std::uint8_t x) { return x == 0; }));
}

TEST_CASE("an UninitializedVector's storage starts on a 64-byte line", "[fresh_memory]") {
  // The solver lays its rows out on whole lines (multigrid.cpp, Level::at); small sizes too,
  // which a plain allocator would give 16-byte alignment.
  for (std::size_t n : {std::size_t(1), std::size_t(5), std::size_t(40), std::size_t(1) << 20}) {
    UninitializedVector<float> v(n);
    CHECK(reinterpret_cast<std::uintptr_t>(v.data()) % 64 == 0);
    UninitializedVector<std::uint8_t> bytes(n);
    CHECK(reinterpret_cast<std::uintptr_t>(bytes.data()) % 64 == 0);
  }
}
