// io/png_encode: what it writes decodes to the pixels it was given, from packed bytes and from
// Cairo's 32-bit words; its bytes do not depend on where the encoding thread's stack lies; and
// its float-to-byte conversions round like std::lround.
#include <png.h>
#include <pthread.h>
#include <sys/mman.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "io/png_decode.hpp"
#include "io/png_encode.hpp"

namespace {

// RGB bytes with every value in each channel, and runs of equal pixels (the encoder's matches).
std::vector<std::uint8_t> pattern(int width, int height) {
  std::vector<std::uint8_t> rgb(size_t(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        rgb[(size_t(y) * width + x) * 3 + c] =
            std::uint8_t(x < width / 2 ? (x * 7 + y * 13 + c * 61) % 256 : y * 5 + c);
  return rgb;
}

}  // namespace

TEST_CASE("PNG encoding round-trips RGB bytes and 0xXXRRGGBB words", "[io][png]") {
  const int w = 61, h = 37;
  const std::vector<std::uint8_t> rgb = pattern(w, h);
  std::vector<std::uint32_t> words(size_t(w) * h);
  for (size_t i = 0; i < words.size(); ++i)
    words[i] = 0x5a000000u | std::uint32_t(rgb[3 * i]) << 16 | std::uint32_t(rgb[3 * i + 1]) << 8 |
               rgb[3 * i + 2];
  const std::vector<std::uint8_t> packed =
      wisp::io::encode_png({rgb.data(), w, h, 3, size_t(w) * 3});
  const std::vector<std::uint8_t> from_words = wisp::io::encode_png(
      {reinterpret_cast<const std::uint8_t*>(words.data()), w, h, 3, size_t(w) * 4, true});
  for (const auto* bytes : {&packed, &from_words}) {
    const wisp::io::RgbImage got = wisp::io::decode_png(bytes->data(), bytes->size(), 4096);
    REQUIRE(got.width == w);
    REQUIRE(got.height == h);
    CHECK(got.pixels == rgb);
  }
  CHECK_THROWS(wisp::io::encode_png({rgb.data(), w, h, 4, size_t(w) * 4, true}));
}

TEST_CASE("PNG encoding round-trips 1 to 4 channels, padded rows, many blocks and IDAT chunks",
          "[io][png]") {
  // 1500 px rows of 4 channels are 6 KB: the encoder compresses about 256 KB of rows at a time,
  // so 200 rows take several blocks. The noise does not compress, so the 3 MB image needs
  // several IDAT chunks (at most 1 MB each). libpng checks every chunk's CRC while it reads.
  for (const bool noise : {false, true}) {
    for (int channels = 1; channels <= 4; ++channels) {
      const int w = noise ? 1024 : 1500, h = noise ? 1024 : 200;
      if (noise && channels != 3) continue;
      const size_t stride = size_t(w) * channels + 5;  // padded rows
      std::vector<std::uint8_t> data(stride * h, 0xee);
      std::uint32_t state = 12345;
      for (int y = 0; y < h; ++y)
        for (int i = 0; i < w * channels; ++i) {
          state = state * 1664525u + 1013904223u;
          data[size_t(y) * stride + i] =
              noise ? std::uint8_t(state >> 24) : std::uint8_t((i / channels) * 3 + y * 7 + i % 5);
        }
      const std::vector<std::uint8_t> png =
          wisp::io::encode_png({data.data(), w, h, channels, stride});
      png_image image{};
      image.version = PNG_IMAGE_VERSION;
      REQUIRE(png_image_begin_read_from_memory(&image, png.data(), png.size()));
      static constexpr png_uint_32 kFormat[5] = {0, PNG_FORMAT_GRAY, PNG_FORMAT_GA, PNG_FORMAT_RGB,
                                                 PNG_FORMAT_RGBA};
      CHECK(image.format == kFormat[channels]);
      image.format = kFormat[channels];
      std::vector<std::uint8_t> decoded(PNG_IMAGE_SIZE(image));
      REQUIRE(png_image_finish_read(&image, nullptr, decoded.data(), 0, nullptr));
      INFO("channels " << channels << (noise ? ", noise" : ""));
      REQUIRE(image.width == png_uint_32(w));
      REQUIRE(image.height == png_uint_32(h));
      int wrong = 0;
      for (int y = 0; y < h; ++y)
        for (int i = 0; i < w * channels; ++i)
          wrong += decoded[size_t(y) * w * channels + i] != data[size_t(y) * stride + i];
      CHECK(wrong == 0);
      if (noise) CHECK(png.size() > (2u << 20));  // so it took three IDAT chunks
    }
  }
}

TEST_CASE("PNG encoding in parts: the rows decode whole across the parts' joins", "[io][png]") {
  // 2.3 MB of filtered rows: two parts, compressed apart, of 550 and 551 rows (the Up filter of a
  // part's first row reads the row before it, in the other part); from 0xXXRRGGBB words, as a
  // frame is written. A join that lost a byte, or a wrong Adler-32, fails libpng's read.
  const int w = 700, h = 1101;
  std::vector<std::uint32_t> words(size_t(w) * h);
  std::vector<std::uint8_t> rgb(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const std::uint8_t r = std::uint8_t(x + y), g = std::uint8_t((x * y) >> 6),
                         b = std::uint8_t(y / 3);
      words[i] = 0xff000000u | std::uint32_t(r) << 16 | std::uint32_t(g) << 8 | b;
      rgb[3 * i] = r, rgb[3 * i + 1] = g, rgb[3 * i + 2] = b;
    }
  const std::vector<std::uint8_t> png = wisp::io::encode_png(
      {reinterpret_cast<const std::uint8_t*>(words.data()), w, h, 3, size_t(w) * 4, true});
  const wisp::io::RgbImage got = wisp::io::decode_png(png.data(), png.size(), 4096);
  REQUIRE(got.width == w);
  REQUIRE(got.height == h);
  REQUIRE(got.pixels.size() == rgb.size());
  size_t wrong = 0;  // (a count: Catch would print all 2.3 million bytes of a failed ==)
  for (size_t i = 0; i < rgb.size(); ++i) wrong += got.pixels[i] != rgb[i];
  CHECK(wrong == 0);
}

TEST_CASE("PNG encoding of a single pixel and of rows longer than a block", "[io][png]") {
  for (const int w : {1, 100000}) {  // a 100000-pixel RGB row is 300 KB: one row a block
    const int h = w == 1 ? 1 : 3;
    std::vector<std::uint8_t> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::uint8_t(i * 31 / 7);
    const std::vector<std::uint8_t> png =
        wisp::io::encode_png({rgb.data(), w, h, 3, size_t(w) * 3});
    const wisp::io::RgbImage got = wisp::io::decode_png(png.data(), png.size(), 100000);
    INFO("width " << w);
    CHECK(got.width == w);
    CHECK(got.height == h);
    CHECK(got.pixels == rgb);
  }
}

TEST_CASE("PNG bytes do not depend on where the encoding thread's stack lies", "[io][png]") {
  // igzip's path for a stream's first byte hashes the stream struct's address (on the encoding
  // thread's stack) where it means the input (png_encode.cpp, deflate_rows): the parse of a
  // stream's start then depended on bits 16-47 of the stack's address, which ASLR sets, and
  // about one process in 3 000 wrote other bytes. Here the image is encoded on threads whose
  // stacks lie 64 KiB apart. The image is tiny, so igzip's hash table is small and the stray slot
  // often meets one the parse uses: before the fix 9 of these 512 stacks gave other bytes.
  const std::uint8_t pixels[] = {1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3};
  const wisp::io::PixelRows image{pixels, 3, 2, 3, 9, false};
  const std::vector<std::uint8_t> reference = wisp::io::encode_png(image);
  constexpr std::size_t kStack = 256 << 10, kStep = 64 << 10;
  constexpr int kPlaces = 512;
  const std::size_t reserved = kStack + kPlaces * kStep;
  void* const base = mmap(nullptr, reserved, PROT_READ | PROT_WRITE,
                          MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  REQUIRE(base != MAP_FAILED);
  struct Job {
    const wisp::io::PixelRows* image;
    std::vector<std::uint8_t> png;
  } job{&image, {}};
  const auto encode = [](void* arg) -> void* {
    auto* j = static_cast<Job*>(arg);
    j->png = wisp::io::encode_png(*j->image);
    return nullptr;
  };
  int differing = 0, ran = 0;
  for (int k = 0; k < kPlaces; ++k) {
    char* stack = static_cast<char*>(base) + k * kStep;
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setstack(&attr, stack, kStack);
    pthread_t thread;
    if (pthread_create(&thread, &attr, encode, &job) == 0) {
      pthread_join(thread, nullptr);
      ++ran;
      differing += job.png != reference;
    }
    pthread_attr_destroy(&attr);
    madvise(stack, kStack, MADV_DONTNEED);  // (the next stack overlaps; keep the memory small)
  }
  munmap(base, reserved);
  CHECK(ran == kPlaces);
  CHECK(differing == 0);
}

TEST_CASE("Channels become bytes as std::lround(clamp(v, 0, 1) * 255)", "[io][png]") {
  std::vector<float> v = {0.0f,
                          -0.0f,
                          -1.0f,
                          1.0f,
                          2.0f,
                          std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(),
                          0.5f / 255,
                          1.5f / 255};
  for (int k = 0; k <= 255; ++k)  // every half, and the floats either side of it
    for (const float x : {(k + 0.5f) / 255, std::nextafter((k + 0.5f) / 255, 0.0f),
                          std::nextafter((k + 0.5f) / 255, 1.0f)})
      v.push_back(x);
  while (v.size() % 3) v.push_back(0.25f);
  const int n = int(v.size() / 3);
  const float *r = v.data(), *g = r + n, *b = g + n;
  std::vector<std::uint32_t> words(n);
  wisp::io::pack_rgb(r, g, b, words.data(), n);
  const auto expected = [](float x) {
    return std::uint32_t(std::lround(std::clamp(x, 0.0f, 1.0f) * 255));
  };
  for (int i = 0; i < n; ++i) {
    INFO(i);
    CHECK(wisp::io::unit_byte(r[i]) == expected(r[i]));
    CHECK(words[i] == (0xff000000u | expected(r[i]) << 16 | expected(g[i]) << 8 | expected(b[i])));
  }
  // 21: through every loop (sixteen at a time where the CPU has AVX-512, four, then one).
  const std::vector<float> nan(21, std::numeric_limits<float>::quiet_NaN());
  words.assign(21, 0);
  wisp::io::pack_rgb(nan.data(), nan.data(), nan.data(), words.data(), 21);
  for (int i = 0; i < 21; ++i) CHECK(words[i] == 0xff000000u);
  CHECK(wisp::io::unit_byte(nan[0]) == 0);
}
