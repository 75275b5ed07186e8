// PNG encoding with libpng at a fast setting (see png_encode.hpp).
#include "io/png_encode.hpp"

#include <png.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <zlib.h>

#include <csetjmp>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace wisp::io {
namespace {

void append(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + length);
}

void flush(png_structp) {}

void warn(png_structp, png_const_charp) {}

// libpng reports errors by longjmp to the setjmp below; nothing with a destructor lives in this
// frame after it, so the jump skips no cleanup.
bool encode_into(png_structp png, png_infop info, const PixelRows& px,
                 std::vector<std::uint8_t>* out) {
  static constexpr int kColourType[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                         PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, out, append, flush);
  png_set_IHDR(png, info, png_uint_32(px.width), png_uint_32(px.height), 8,
               kColourType[px.channels], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  // Up alone: one subtraction per byte, and smooth shading compresses almost as well as with the
  // adaptive choice among all five filters, which tries each on every row.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  // Run-length matches only (distance 1: after the Up filter, runs of zeros in flat and smooth
  // parts): faster than level 1's hash chains, and smaller here (frame 36 at 1024^2: 212 KB
  // against 228 KB).
  png_set_compression_level(png, 1);
  png_set_compression_strategy(png, Z_RLE);
  png_write_info(png, info);
  if (px.xrgb32) {  // libpng drops the filler byte and orders the others as RGB
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    png_set_bgr(png);
    png_set_filler(png, 0, PNG_FILLER_AFTER);
#else
    png_set_filler(png, 0, PNG_FILLER_BEFORE);
#endif
  }
  for (int y = 0; y < px.height; ++y)
    png_write_row(png, const_cast<png_bytep>(px.data + std::size_t(y) * px.stride));
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

void pack_rgb(const float* r, const float* g, const float* b, std::uint32_t* out, int n) {
  int x = 0;
#if defined(__SSE2__)
  // unit_byte four at a time, the same operations: max(v, 0) takes 0 for NaN like unit_byte, and
  // the truncation and the comparison with a half are exact as there.
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), scale = _mm_set1_ps(255.0f),
               half = _mm_set1_ps(0.5f);
  const auto bytes = [&](const float* v) {
    const __m128 c = _mm_mul_ps(_mm_min_ps(_mm_max_ps(_mm_loadu_ps(v), zero), one), scale);
    const __m128i i = _mm_cvttps_epi32(c);
    const __m128 up = _mm_cmpge_ps(_mm_sub_ps(c, _mm_cvtepi32_ps(i)), half);
    return _mm_sub_epi32(i, _mm_castps_si128(up));  // up is all ones (-1) where rounding up
  };
  const __m128i alpha = _mm_set1_epi32(int(0xff000000u));
  for (; x + 4 <= n; x += 4) {
    const __m128i px = _mm_or_si128(_mm_or_si128(alpha, _mm_slli_epi32(bytes(r + x), 16)),
                                    _mm_or_si128(_mm_slli_epi32(bytes(g + x), 8), bytes(b + x)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x), px);
  }
#endif
  for (; x < n; ++x)
    out[x] = 0xff000000u | std::uint32_t(unit_byte(r[x])) << 16 |
             std::uint32_t(unit_byte(g[x])) << 8 | unit_byte(b[x]);
}

std::vector<std::uint8_t> encode_png(const PixelRows& px) {
  if (px.channels < 1 || px.channels > 4 || px.width <= 0 || px.height <= 0 || !px.data ||
      (px.xrgb32 && px.channels != 3))
    throw std::runtime_error("PNG encoding failed: bad image layout");
  std::vector<std::uint8_t> out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, warn);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = info && encode_into(png, info, px, &out);
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error("PNG encoding failed");
  return out;
}

void write_png_fast(const std::filesystem::path& path, const PixelRows& pixels) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = encode_png(pixels);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::unique_ptr<std::FILE, decltype(&std::fclose)> f(std::fopen(tmp.c_str(), "wb"),
                                                         std::fclose);
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f.get()) != bytes.size() ||
        std::fflush(f.get()) != 0)
      throw std::runtime_error(path.string() + ": cannot write the PNG file");
  });
}

}  // namespace wisp::io
