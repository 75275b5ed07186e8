// .hair reader and writer: see hair_file.hpp.
#include "io/hair_file.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/input_file.hpp"

namespace wisp::io {
namespace {

constexpr std::uint32_t kSegments = 1, kPoints = 2, kThickness = 4, kTransparency = 8, kColors = 16;
constexpr std::size_t kHeaderSize = 128, kInfoSize = 88;

template <class T>
T read_at(const std::string& bytes, std::size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

template <class T>
void append(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

}  // namespace

HairFile read_hair_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string bytes = read_input_file(path, ".hair file");
  if (bytes.size() < kHeaderSize)
    throw std::runtime_error(name + ": truncated .hair header (" + std::to_string(bytes.size()) +
                             " of 128 bytes)");
  if (std::memcmp(bytes.data(), "HAIR", 4) != 0)
    throw std::runtime_error(name + ": not a .hair file (signature is not \"HAIR\")");
  HairFile hair;
  const auto strands = read_at<std::uint32_t>(bytes, 4);
  const auto points = read_at<std::uint32_t>(bytes, 8);
  const auto flags = read_at<std::uint32_t>(bytes, 12);
  hair.default_segments = read_at<std::uint32_t>(bytes, 16);
  hair.default_thickness = read_at<float>(bytes, 20);
  hair.default_transparency = read_at<float>(bytes, 24);
  for (int k = 0; k < 3; ++k) hair.default_color[k] = read_at<float>(bytes, 28 + 4 * k);
  hair.info.assign(bytes.data() + 40, strnlen(bytes.data() + 40, kInfoSize));
  hair.has_segments = flags & kSegments;
  if (strands > points)
    throw std::runtime_error(name + ": the header announces " + std::to_string(strands) +
                             " strands but only " + std::to_string(points) + " points");
  if (!(flags & kPoints)) throw std::runtime_error(name + ": the .hair file has no points array");
  if (!hair.has_segments && hair.default_segments == 0)
    throw std::runtime_error(name + ": no segments array and default segments is 0");

  // Expected size, computed in 64 bits before allocating anything.
  const std::uint64_t n = points;
  std::uint64_t expected = kHeaderSize + (hair.has_segments ? 2ull * strands : 0) + 12 * n;
  if (flags & kThickness) expected += 4 * n;
  if (flags & kTransparency) expected += 4 * n;
  if (flags & kColors) expected += 12 * n;
  if (bytes.size() < expected)
    throw std::runtime_error(name + ": truncated .hair file (" + std::to_string(bytes.size()) +
                             " bytes, the header announces " + std::to_string(expected) + ")");
  if (bytes.size() > expected)
    throw std::runtime_error(name + ": " + std::to_string(bytes.size() - expected) +
                             " unexpected bytes after the last array");

  std::size_t at = kHeaderSize;
  std::vector<std::uint32_t> seg(strands, hair.default_segments);
  if (hair.has_segments)
    for (std::uint32_t s = 0; s < strands; ++s, at += 2) seg[s] = read_at<std::uint16_t>(bytes, at);
  std::uint64_t total = 0;
  for (std::uint32_t s : seg) total += s + 1ull;
  if (total != n)
    throw std::runtime_error(name + ": the segments add up to " + std::to_string(total) +
                             " points but the header says " + std::to_string(n));
  hair.strands.resize(strands);
  for (std::uint32_t s = 0; s < strands; ++s) {
    hair.strands[s].resize(seg[s] + 1);
    for (auto& p : hair.strands[s]) {
      for (int k = 0; k < 3; ++k, at += 4) p[k] = read_at<float>(bytes, at);
      if (!p.allFinite())
        throw std::runtime_error(name + ": strand " + std::to_string(s) +
                                 " has a non-finite point");
    }
  }
  const auto floats = [&](std::vector<float>& out) {
    out.resize(n);
    for (auto& v : out) v = read_at<float>(bytes, at), at += 4;
  };
  if (flags & kThickness) floats(hair.thickness);
  if (flags & kTransparency) floats(hair.transparency);
  if (flags & kColors) {
    hair.colors.resize(n);
    for (auto& c : hair.colors)
      for (int k = 0; k < 3; ++k, at += 4) c[k] = read_at<float>(bytes, at);
  }
  return hair;
}

void write_hair_file(const std::filesystem::path& path, const HairFile& hair) {
  std::uint64_t n = 0;
  for (const auto& s : hair.strands) {
    if (s.size() < 1 || s.size() > 65536)
      throw std::invalid_argument("write_hair_file: a strand needs 1 to 65536 points");
    if (!hair.has_segments && s.size() != hair.default_segments + 1ull)
      throw std::invalid_argument(
          "write_hair_file: without a segments array every strand needs "
          "default_segments + 1 points");
    n += s.size();
  }
  if (n > 0xFFFFFFFFull) throw std::invalid_argument("write_hair_file: too many points");
  const auto check = [&](std::size_t size, const char* what) {
    if (size != 0 && size != n)
      throw std::invalid_argument(std::string("write_hair_file: ") + what + " has " +
                                  std::to_string(size) + " values for " + std::to_string(n) +
                                  " points");
  };
  check(hair.thickness.size(), "thickness");
  check(hair.transparency.size(), "transparency");
  check(hair.colors.size(), "colors");
  std::uint32_t flags = kPoints | (hair.has_segments ? kSegments : 0);
  if (!hair.thickness.empty()) flags |= kThickness;
  if (!hair.transparency.empty()) flags |= kTransparency;
  if (!hair.colors.empty()) flags |= kColors;

  std::string out = "HAIR";
  append(out, static_cast<std::uint32_t>(hair.strands.size()));
  append(out, static_cast<std::uint32_t>(n));
  append(out, flags);
  append(out, hair.default_segments);
  append(out, hair.default_thickness);
  append(out, hair.default_transparency);
  for (int k = 0; k < 3; ++k) append(out, hair.default_color[k]);
  std::string info = hair.info.substr(0, kInfoSize);
  info.resize(kInfoSize, '\0');
  out += info;
  if (hair.has_segments)
    for (const auto& s : hair.strands) append(out, static_cast<std::uint16_t>(s.size() - 1));
  for (const auto& s : hair.strands)
    for (const auto& p : s)
      for (int k = 0; k < 3; ++k) append(out, static_cast<float>(p[k]));
  for (float v : hair.thickness) append(out, v);
  for (float v : hair.transparency) append(out, v);
  for (const auto& c : hair.colors)
    for (int k = 0; k < 3; ++k) append(out, c[k]);
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    f.write(out.data(), static_cast<std::streamsize>(out.size()));
    if (!f) throw std::runtime_error(tmp.string() + ": write failed");
  });
}

}  // namespace wisp::io
