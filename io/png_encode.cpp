// PNG encoding: the file's chunks written here around ISA-L's igzip (see png_encode.hpp).
#include "io/png_encode.hpp"

#include <isa-l/igzip_lib.h>
#include <tbb/parallel_for.h>
#include <zlib.h>
#if defined(__AVX512F__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace wisp::io {
namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

// A chunk: its length, type and data, and the CRC-32 of type and data (PNG spec, 5.3).
void put_chunk(std::vector<std::uint8_t>& out, const char (&type)[5], const std::uint8_t* data,
               std::size_t n) {
  put_u32(out, std::uint32_t(n));
  const auto* t = reinterpret_cast<const std::uint8_t*>(type);
  out.insert(out.end(), t, t + 4);
  if (n > 0) out.insert(out.end(), data, data + n);
  uLong crc = crc32(0L, t, 4);
  if (n > 0) crc = crc32_z(crc, data, n);
  put_u32(out, std::uint32_t(crc));
}

// Row y of the image as packed bytes (RGB from 0xXXRRGGBB words).
void packed_row(const PixelRows& px, int y, std::uint8_t* row) {
  const std::uint8_t* src = px.data + std::size_t(y) * px.stride;
  if (!px.xrgb32) {
    std::copy(src, src + std::size_t(px.width) * px.channels, row);
    return;
  }
  for (int x = 0; x < px.width; ++x) {  // native-endian words 0xXXRRGGBB
    std::uint32_t word;
    std::memcpy(&word, src + 4 * std::size_t(x), 4);
    row[3 * std::size_t(x)] = std::uint8_t(word >> 16);
    row[3 * std::size_t(x) + 1] = std::uint8_t(word >> 8);
    row[3 * std::size_t(x) + 2] = std::uint8_t(word);
  }
}

constexpr std::uint8_t kFilterUp = 2;  // PNG's filter type "Up" (the PNG spec, 9.2)

// Rows y0 .. y1 - 1, each as PNG stores it: the filter type byte (2, Up) and the row minus the
// row above (the first row of the image is its own bytes: Up against a row of zeros), deflated
// (raw, no zlib wrapper) in blocks of rows so that the filtered rows are never whole in memory.
// The last part of an image ends the deflate stream; the others end on a full flush (byte
// aligned, no history), so that the parts, compressed apart, join into one stream. Returns the
// bytes and, in `adler`, the Adler-32 of the filtered rows.
//
// The part's first byte (its first row's filter type) is written here as a stored block and
// given to igzip as the history its stream starts from. igzip's level-1 body has a path for a
// stream's very first byte (`.write_first_byte` in ISA-L 2.30's igzip_icf_body.asm) that hashes
// the register holding the stream struct's address where it means the input's next bytes: the
// second position's hash-table entry goes to a slot that depends on where the stack lies. The
// output still decodes to the same rows, but about one process in 3 000 (ASLR places the stack)
// parsed the start of a stream differently, so renders were now and then other bytes
// (docs/render.md). With a history igzip never takes that path; the stored block costs 6 bytes.
std::vector<std::uint8_t> deflate_rows(const PixelRows& px, int y0, int y1, bool last,
                                       std::uint32_t& adler) {
  const std::size_t row_bytes = std::size_t(px.width) * px.channels;
  std::vector<std::uint8_t> level_buf(ISAL_DEF_LVL1_DEFAULT);
  isal_zstream z;
  isal_deflate_init(&z);
  z.level = 1;
  z.level_buf = level_buf.data();
  z.level_buf_size = std::uint32_t(level_buf.size());
  z.gzip_flag = IGZIP_DEFLATE;
  // Every row's filter type is Up, so the part's first byte is known: the stored block (not the
  // last: header bits 000, then padding to the byte) of that one byte, LEN 1 and NLEN ~1,
  // little-endian (RFC 1951, 3.2.4), and igzip's history.
  std::uint8_t up = kFilterUp;
  std::vector<std::uint8_t> out = {0x00, 0x01, 0x00, 0xfe, 0xff, up};
  const std::size_t stored = out.size();
  if (isal_deflate_set_dict(&z, &up, 1) != COMP_OK)
    throw std::runtime_error("PNG encoding failed: igzip");
  adler = 1;  // Adler-32 of no bytes
  const auto deflate = [&](std::uint8_t* data, std::size_t n, bool end) {
    adler = isal_adler32(adler, data, n);
    if (z.total_in == 0) ++data, --n;  // the first block's first byte: in the stored block
    z.next_in = data;
    z.avail_in = std::uint32_t(n);
    z.end_of_stream = end && last ? 1 : 0;
    z.flush = end && !last ? FULL_FLUSH : NO_FLUSH;
    do {
      if (out.size() - stored - z.total_out < 65536)
        out.resize(std::max<std::size_t>(2 * out.size(), 65536));
      z.next_out = out.data() + stored + z.total_out;
      z.avail_out = std::uint32_t(out.size() - stored - z.total_out);
      if (isal_deflate(&z) != COMP_OK) throw std::runtime_error("PNG encoding failed: igzip");
      // All input taken and output room left over: a flush is complete (igzip_lib.h).
    } while (z.avail_in > 0 ||
             (end && (last ? z.internal_state.state != ZSTATE_END : z.avail_out == 0)));
  };
  // About 256 KB of filtered rows a block, at least one row.
  const int rows_per_block = int(std::max<std::size_t>(1, (256 << 10) / (row_bytes + 1)));
  std::vector<std::uint8_t> block(std::size_t(std::min(rows_per_block, y1 - y0)) * (row_bytes + 1));
  std::vector<std::uint8_t> row(row_bytes), above(row_bytes, 0);
  if (y0 > 0) packed_row(px, y0 - 1, above.data());
  int in_block = 0;
  for (int y = y0; y < y1; ++y) {
    packed_row(px, y, row.data());
    std::uint8_t* f = &block[std::size_t(in_block) * (row_bytes + 1)];
    f[0] = kFilterUp;
    for (std::size_t i = 0; i < row_bytes; ++i) f[1 + i] = std::uint8_t(row[i] - above[i]);
    row.swap(above);
    if (++in_block == rows_per_block || y + 1 == y1) {
      deflate(block.data(), std::size_t(in_block) * (row_bytes + 1), y + 1 == y1);
      in_block = 0;
    }
  }
  out.resize(stored + z.total_out);
  return out;
}

// The image's filtered rows as one zlib stream, compressed in parts of at least kPartBytes by the
// worker threads (pigz's way: each part a deflate stream of its own, joined on full flushes,
// the Adler-32s combined). The parts follow from the image's size alone, so the bytes do not
// depend on the thread count. A 1024^2 frame is three parts.
std::vector<std::uint8_t> compressed_rows(const PixelRows& px) {
  const std::size_t row_bytes = std::size_t(px.width) * px.channels;
  if ((row_bytes + 1) * std::size_t(px.height) >= 0xffffffffu)
    throw std::runtime_error("PNG encoding failed: image too large");
  constexpr std::size_t kPartBytes = std::size_t(1) << 20;
  constexpr int kMostParts = 8;
  const int parts = int(std::clamp<std::size_t>((row_bytes + 1) * px.height / kPartBytes, 1,
                                                std::min(kMostParts, px.height)));
  // Part k is rows row(k) .. row(k + 1) - 1: none empty, since there are no more parts than rows.
  const auto row = [&](int k) { return int(std::int64_t(k) * px.height / parts); };
  std::vector<std::vector<std::uint8_t>> deflated(parts);
  std::vector<std::uint32_t> adlers(parts);
  const auto deflate_part = [&](int k) {
    deflated[k] = deflate_rows(px, row(k), row(k + 1), k + 1 == parts, adlers[k]);
  };
  if (parts == 1)
    deflate_part(0);  // on the calling thread (an SVG's hair image, a small frame)
  else
    tbb::parallel_for(0, parts, deflate_part);
  std::vector<std::uint8_t> out = {0x78, 0x01};  // zlib: deflate, 32 KB window, fastest
  uLong adler = adlers[0];
  for (int k = 0; k < parts; ++k) {
    out.insert(out.end(), deflated[k].begin(), deflated[k].end());
    if (k > 0)
      adler = adler32_combine(adler, adlers[k], z_off_t((row_bytes + 1) * (row(k + 1) - row(k))));
  }
  put_u32(out, std::uint32_t(adler));
  return out;
}

}  // namespace

void pack_rgb(const float* r, const float* g, const float* b, std::uint32_t* out, int n) {
  int x = 0;
#if defined(__AVX512F__)
  // Sixteen at a time, the same operations as the SSE2 loop below (and so unit_byte's bytes).
  {
    const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f),
                 scale = _mm512_set1_ps(255.0f), half = _mm512_set1_ps(0.5f);
    const auto bytes = [&](const float* v) {
      const __m512 c =
          _mm512_mul_ps(_mm512_min_ps(_mm512_max_ps(_mm512_loadu_ps(v), zero), one), scale);
      const __m512i i = _mm512_cvttps_epi32(c);
      const __mmask16 up =
          _mm512_cmp_ps_mask(_mm512_sub_ps(c, _mm512_cvtepi32_ps(i)), half, _CMP_GE_OQ);
      return _mm512_mask_add_epi32(i, up, i, _mm512_set1_epi32(1));
    };
    const __m512i alpha = _mm512_set1_epi32(int(0xff000000u));
    for (; x + 16 <= n; x += 16) {
      const __m512i px =
          _mm512_or_si512(_mm512_or_si512(alpha, _mm512_slli_epi32(bytes(r + x), 16)),
                          _mm512_or_si512(_mm512_slli_epi32(bytes(g + x), 8), bytes(b + x)));
      _mm512_storeu_si512(out + x, px);
    }
  }
#endif
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
  static constexpr std::uint8_t kColourType[5] = {0, 0, 4, 2, 6};  // grey, grey+alpha, RGB, RGBA
  if (px.channels < 1 || px.channels > 4 || px.width <= 0 || px.height <= 0 || !px.data ||
      (px.xrgb32 && px.channels != 3))
    throw std::runtime_error("PNG encoding failed: bad image layout");
  const std::vector<std::uint8_t> idat = compressed_rows(px);
  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  out.reserve(idat.size() + 64 + idat.size() / (1 << 20) * 12);
  std::vector<std::uint8_t> header;
  put_u32(header, std::uint32_t(px.width));
  put_u32(header, std::uint32_t(px.height));
  // 8 bits a channel, the colour type, deflate, adaptive filtering (per row), no interlace.
  header.insert(header.end(), {8, kColourType[px.channels], 0, 0, 0});
  put_chunk(out, "IHDR", header.data(), header.size());
  for (std::size_t at = 0; at < idat.size(); at += 1 << 20)  // IDAT chunks of at most 1 MB
    put_chunk(out, "IDAT", idat.data() + at, std::min<std::size_t>(1 << 20, idat.size() - at));
  put_chunk(out, "IEND", nullptr, 0);
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
