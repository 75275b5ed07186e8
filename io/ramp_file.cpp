// Reading toon ramps (see ramp_file.hpp). The PNG's chunk structure, checksums and size are
// checked here before the decoder sees it: libpng reports a truncated or corrupt file on stderr
// before failing, and a decoder fails a huge one with its own text; neither names the field.
#include "io/ramp_file.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/input_file.hpp"
#include "io/png_decode.hpp"

namespace wisp::io {
namespace {

std::uint32_t big_endian(const std::string& b, std::size_t at) {
  return std::uint32_t(std::uint8_t(b[at])) << 24 | std::uint32_t(std::uint8_t(b[at + 1])) << 16 |
         std::uint32_t(std::uint8_t(b[at + 2])) << 8 | std::uint32_t(std::uint8_t(b[at + 3]));
}

std::uint32_t crc32(const std::string& b, std::size_t at, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = at; i < at + n; ++i) {
    c ^= std::uint8_t(b[i]);
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

// Walks the chunks of a PNG: signature, IHDR first with a size in [1, kMaxRampSide], every
// chunk whole with a matching CRC, IDAT present, IEND last. Throws naming `name`.
void check_png(const std::string& b, const std::string& name) {
  const auto fail = [&](const std::string& what) { throw std::runtime_error(name + ": " + what); };
  if (b.size() < 8 || b.compare(0, 8, "\x89PNG\r\n\x1a\n", 8) != 0)
    fail("not a PNG image (ramps are PNG files)");
  std::size_t at = 8;
  bool idat = false;
  for (int index = 0;; ++index) {
    if (at + 12 > b.size()) fail("truncated PNG image (no IEND chunk)");
    const std::uint32_t length = big_endian(b, at);
    const std::string type = b.substr(at + 4, 4);
    // PNG chunk types are four ASCII letters; checked before a message quotes one.
    for (const char c : type)
      if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z')))
        fail("corrupt PNG image (chunk " + std::to_string(index) +
             " has a type that is not letters)");
    if (length > b.size() - at - 12) fail("truncated PNG image (in a " + type + " chunk)");
    if (crc32(b, at + 4, 4 + length) != big_endian(b, at + 8 + length))
      fail("corrupt PNG image (checksum of a " + type + " chunk)");
    if (index == 0) {
      if (type != "IHDR" || length != 13) fail("corrupt PNG image (no IHDR chunk first)");
      const std::uint32_t w = big_endian(b, at + 8), h = big_endian(b, at + 12);
      if (w < 1 || h < 1 || w > kMaxRampSide || h > kMaxRampSide)
        fail("a " + std::to_string(w) + "x" + std::to_string(h) +
             " image; a ramp's sides must be 1 to " + std::to_string(kMaxRampSide) + " pixels");
    }
    idat |= type == "IDAT";
    at += 12 + length;
    if (type == "IEND") break;
  }
  if (!idat) fail("corrupt PNG image (no pixel data)");
}

}  // namespace

std::shared_ptr<const vector::ToonRamp> read_ramp(const std::filesystem::path& path) {
  const std::string bytes = read_input_file(path, "ramp image");
  check_png(bytes, path.string());
  RgbImage img;
  try {
    img =
        decode_png(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), kMaxRampSide);
  } catch (const std::runtime_error&) {
    throw std::runtime_error(path.string() + ": cannot decode the PNG image");
  }
  auto ramp = std::make_shared<vector::ToonRamp>();
  ramp->width = img.width;
  ramp->height = img.height;
  ramp->source = path.string();
  ramp->pixels.reserve(size_t(img.width) * img.height);
  for (size_t i = 0; i < img.pixels.size(); i += 3)
    ramp->pixels.emplace_back(img.pixels[i] / 255.0f, img.pixels[i + 1] / 255.0f,
                              img.pixels[i + 2] / 255.0f);
  return ramp;
}

}  // namespace wisp::io
