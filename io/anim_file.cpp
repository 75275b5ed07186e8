// .wsim reader and writer: see anim_file.hpp.
#include "io/anim_file.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "io/atomic_file.hpp"
#include "io/input_file.hpp"

namespace wisp::io {
namespace {

constexpr std::uint32_t kWidthsFlag = 1;  // the header's flags: clump widths follow the head

std::uint64_t fnv1a(const char* data, std::size_t n) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void vec(const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) put(v[k]);
  }
  std::string out;
};

// Bounds-checked reads; running out is a truncated file.
class Reader {
 public:
  Reader(const std::string& bytes, std::size_t end, std::string name)
      : bytes_(bytes), end_(end), name_(std::move(name)) {}
  template <class T>
  T get(const char* what) {
    if (at_ + sizeof(T) > end_)
      throw std::runtime_error(name_ + ": truncated .wsim file (ends inside the " + what + ")");
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  Eigen::Vector3d vec(const char* what) {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = get<double>(what);
    return v;
  }
  std::size_t at() const { return at_; }

 private:
  const std::string& bytes_;
  std::size_t end_, at_ = 0;
  std::string name_;
};

}  // namespace

void write_animation(const std::filesystem::path& path, const sim::Animation& anim) {
  Writer w;
  w.out = "WSIM";
  w.put(kAnimVersion);
  w.put(std::uint32_t{anim.widths.empty() ? 0u : kWidthsFlag});
  w.put(anim.fps);
  w.put(static_cast<std::uint32_t>(anim.frames.size()));
  const std::vector<sim::Polyline> none;
  const auto& first = anim.frames.empty() ? none : anim.frames.front().strands;
  w.put(static_cast<std::uint32_t>(first.size()));
  for (const auto& s : first) w.put(static_cast<std::uint32_t>(s.size()));
  const sim::HeadGeometry& h = anim.head;
  w.put(static_cast<std::uint32_t>(h.shape));
  w.vec(h.radii);
  w.put(static_cast<std::uint32_t>(h.mesh.vertices.size()));
  w.put(static_cast<std::uint32_t>(h.mesh.triangles.size()));
  for (const auto& v : h.mesh.vertices) w.vec(v);
  for (const auto& t : h.mesh.triangles)
    for (int k = 0; k < 3; ++k) w.put(static_cast<std::int32_t>(t[k]));
  if (!anim.widths.empty()) {
    if (anim.widths.size() != first.size())
      throw std::invalid_argument("write_animation: clump widths for " +
                                  std::to_string(anim.widths.size()) + " strands, frames have " +
                                  std::to_string(first.size()));
    for (std::size_t s = 0; s < first.size(); ++s) {
      if (anim.widths[s].size() != first[s].size())
        throw std::invalid_argument("write_animation: strand " + std::to_string(s) +
                                    " has clump widths for another sample count");
      for (double v : anim.widths[s]) w.put(v);
    }
  }
  for (const auto& f : anim.frames) {
    if (f.strands.size() != first.size())
      throw std::invalid_argument("write_animation: frame " + std::to_string(f.frame) +
                                  " has a different number of strands");
    w.put(static_cast<std::uint32_t>(f.frame));
    w.put(f.time);
    w.vec(f.head.position);
    const Eigen::Quaterniond& q = f.head.rotation;
    for (double c : {q.w(), q.x(), q.y(), q.z()}) w.put(c);
    for (std::size_t s = 0; s < f.strands.size(); ++s) {
      if (f.strands[s].size() != first[s].size())
        throw std::invalid_argument("write_animation: strand " + std::to_string(s) +
                                    " changes its sample count at frame " +
                                    std::to_string(f.frame));
      for (const auto& p : f.strands[s]) w.vec(p);
    }
  }
  w.put(fnv1a(w.out.data(), w.out.size()));
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    f.write(w.out.data(), static_cast<std::streamsize>(w.out.size()));
    if (!f) throw std::runtime_error(tmp.string() + ": write failed");
  });
}

sim::Animation read_animation(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string bytes = read_input_file(path, "animation file");
  if (bytes.size() < 4 || std::memcmp(bytes.data(), "WSIM", 4) != 0)
    throw std::runtime_error(name + ": not a .wsim animation (bad signature)");
  if (bytes.size() < 8 + 8) throw std::runtime_error(name + ": truncated .wsim file");
  const std::size_t body = bytes.size() - 8;  // everything but the checksum
  Reader r(bytes, body, name);
  r.get<std::uint32_t>("signature");
  const auto version = r.get<std::uint32_t>("header");
  if (version != kAnimVersion)
    throw std::runtime_error(name + ": .wsim version " + std::to_string(version) +
                             " is not supported (this wisp reads version 1)");
  const auto flags = r.get<std::uint32_t>("header");
  if (flags & ~kWidthsFlag)
    throw std::runtime_error(name + ": unknown .wsim flags " + std::to_string(flags));
  sim::Animation anim;
  anim.fps = r.get<double>("header");
  if (!(anim.fps > 0 && anim.fps <= 1000))
    throw std::runtime_error(name + ": fps " + std::to_string(anim.fps) + " is not in (0, 1000]");
  const auto frames = r.get<std::uint32_t>("header");
  const auto strands = r.get<std::uint32_t>("header");
  if (frames == 0) throw std::runtime_error(name + ": the animation has no frames");
  if (strands > (body - r.at()) / 4)
    throw std::runtime_error(name + ": truncated .wsim file (strand table)");
  std::vector<std::uint32_t> samples(strands);
  std::uint64_t total = 0;
  for (auto& n : samples) {
    total += n = r.get<std::uint32_t>("strand table");
    if (n < 2) throw std::runtime_error(name + ": a strand has fewer than 2 samples");
  }
  const auto shape = r.get<std::uint32_t>("head");
  if (shape > static_cast<std::uint32_t>(sim::HeadKind::Mesh))
    throw std::runtime_error(name + ": unknown head shape " + std::to_string(shape));
  anim.head.shape = static_cast<sim::HeadKind>(shape);
  anim.head.radii = r.vec("head");
  if (!(anim.head.radii.allFinite() && anim.head.radii.minCoeff() > 0 &&
        anim.head.radii.maxCoeff() <= 10))
    throw std::runtime_error(name + ": head radii must be in (0, 10] m");
  const std::uint64_t vertices = r.get<std::uint32_t>("head");
  const std::uint64_t triangles = r.get<std::uint32_t>("head");
  if (anim.head.shape == sim::HeadKind::Mesh && triangles == 0)
    throw std::runtime_error(name + ": the head is a mesh without triangles");
  // Check the announced size before allocating.
  const std::uint64_t frame_bytes = 4 + 8 + 24 + 32 + 24 * total;
  const std::uint64_t widths = flags & kWidthsFlag ? total : 0;
  const std::uint64_t expected =
      r.at() + 24 * vertices + 12 * triangles + 8 * widths + frames * frame_bytes;
  if (expected > body)
    throw std::runtime_error(name + ": truncated .wsim file (" + std::to_string(bytes.size()) +
                             " bytes, the header announces " + std::to_string(expected + 8) + ")");
  if (expected < body)
    throw std::runtime_error(name + ": " + std::to_string(body - expected) +
                             " unexpected bytes before the checksum");
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + body, 8);
  if (stored != fnv1a(bytes.data(), body))
    throw std::runtime_error(name + ": checksum mismatch: the .wsim file is corrupt");

  // Positions stay near the head: the projection and the rasterizer take them as they are.
  const auto in_world = [&](const Eigen::Vector3d& p, const char* what) {
    if (!(p.allFinite() && p.norm() <= sim::kMaxWorldMetres))
      throw std::runtime_error(name + ": " + what + " is not within " +
                               std::to_string(int(sim::kMaxWorldMetres)) + " m of the head");
    return p;
  };
  anim.head.mesh.vertices.resize(vertices);
  for (auto& v : anim.head.mesh.vertices) v = in_world(r.vec("head mesh"), "a head vertex");
  anim.head.mesh.triangles.resize(triangles);
  for (auto& t : anim.head.mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      t[k] = r.get<std::int32_t>("head mesh");
      if (t[k] < 0 || static_cast<std::uint64_t>(t[k]) >= vertices)
        throw std::runtime_error(name + ": a head triangle refers to a missing vertex");
    }
  }
  if (widths > 0) {
    anim.widths.resize(strands);
    for (std::uint32_t s = 0; s < strands; ++s) {
      anim.widths[s].resize(samples[s]);
      for (double& v : anim.widths[s]) {
        v = r.get<double>("clump widths");
        if (!(v >= 0 && v <= 10))
          throw std::runtime_error(name + ": a clump width is not in [0, 10] m");
      }
    }
  }
  anim.frames.resize(frames);
  for (auto& f : anim.frames) {
    f.frame = static_cast<int>(r.get<std::uint32_t>("frame"));
    f.time = r.get<double>("frame");
    f.head.position = in_world(r.vec("frame"), "a head position");
    const double qw = r.get<double>("frame"), qx = r.get<double>("frame"),
                 qy = r.get<double>("frame"), qz = r.get<double>("frame");
    f.head.rotation = Eigen::Quaterniond(qw, qx, qy, qz);
    const double norm = f.head.rotation.norm();
    if (!(std::abs(norm - 1) < 1e-6))
      throw std::runtime_error(name + ": frame " + std::to_string(f.frame) +
                               ": the head rotation is not a unit quaternion");
    f.strands.resize(strands);
    for (std::uint32_t s = 0; s < strands; ++s) {
      f.strands[s].resize(samples[s]);
      for (auto& p : f.strands[s]) p = in_world(r.vec("frame"), "a strand sample");
    }
  }
  return anim;
}

}  // namespace wisp::io
