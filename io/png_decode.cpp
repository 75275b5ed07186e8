// PNG decoding with libpng (see png_decode.hpp).
#include "io/png_decode.hpp"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <stdexcept>

#include "io/input_file.hpp"

namespace wisp::io {
namespace {

struct Source {
  const std::uint8_t* data;
  std::size_t size, at = 0;
};

// libpng's errors end in a longjmp back into decode_into; the message is kept for the exception.
struct Failure {
  char message[160] = "";
};

void fail(png_structp png, png_const_charp message) {
  auto* f = static_cast<Failure*>(png_get_error_ptr(png));
  std::strncpy(f->message, message, sizeof f->message - 1);
  png_longjmp(png, 1);
}

void ignore_warning(png_structp, png_const_charp) {}

void read_bytes(png_structp png, png_bytep out, png_size_t n) {
  auto* s = static_cast<Source*>(png_get_io_ptr(png));
  if (n > s->size - s->at) png_error(png, "truncated PNG image");
  std::memcpy(out, s->data + s->at, n);
  s->at += n;
}

// Nothing with a destructor lives in this frame (the pixels and the row pointers are the caller's
// vectors), so the longjmp of an error skips no cleanup.
bool decode_into(png_structp png, png_infop info, Source* source, int max_side, RgbImage* out,
                 std::vector<png_bytep>* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, source, read_bytes);
  png_set_user_limits(png, png_uint_32(max_side), png_uint_32(max_side));
  png_read_info(png, info);
  const int depth = png_get_bit_depth(png, info), colour = png_get_color_type(png, info);
  // The transforms, in the order OpenCV's PNG decoder asks for them.
  if (depth == 16) png_set_strip_16(png);
  png_set_strip_alpha(png);
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if ((colour & PNG_COLOR_MASK_COLOR) == 0 && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if ((colour & PNG_COLOR_MASK_COLOR) == 0) png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out->width = int(png_get_image_width(png, info));
  out->height = int(png_get_image_height(png, info));
  if (png_get_rowbytes(png, info) != std::size_t(out->width) * 3)
    png_error(png, "unexpected PNG row layout");
  out->pixels.resize(std::size_t(out->width) * out->height * 3);
  rows->resize(out->height);
  for (int y = 0; y < out->height; ++y)
    (*rows)[y] = out->pixels.data() + std::size_t(y) * out->width * 3;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

RgbImage decode_png(const std::uint8_t* data, std::size_t size, int max_side) {
  if (size < 8 || png_sig_cmp(data, 0, 8) != 0) throw std::runtime_error("not a PNG image");
  Failure failure;
  Source source{data, size};
  RgbImage image;
  std::vector<png_bytep> rows;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &failure, fail, ignore_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = info && decode_into(png, info, &source, max_side, &image, &rows);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!ok)
    throw std::runtime_error(std::string("cannot decode the PNG image (") +
                             (failure.message[0] ? failure.message : "out of memory") + ")");
  return image;
}

RgbImage read_png(const std::filesystem::path& path, const std::string& what, int max_side) {
  const std::string bytes = read_input_file(path, what);
  try {
    return decode_png(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), max_side);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

}  // namespace wisp::io
