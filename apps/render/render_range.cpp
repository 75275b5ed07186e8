// A range of frames rendered into a folder, resumably (see render_range.hpp).
#include "apps/render/render_range.hpp"

#include <tbb/parallel_invoke.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <regex>
#include <stdexcept>

#include "apps/render/frame_writer.hpp"
#include "apps/render/render_stats.hpp"
#include "diffusion/multigrid.hpp"
#include "diffusion/timer.hpp"
#include "io/atomic_file.hpp"
#include "io/contact_sheet.hpp"
#include "io/video_file.hpp"

namespace wisp::render {
namespace {

namespace fs = std::filesystem;
using diffusion::Clock;
using diffusion::ms_since;

// One past the last frame of block b that is to be written (b * block when there is none).
int block_end(const RangePlan& plan, int b) {
  const int n = int(plan.write.size());
  int end = (b + 1) * plan.block;
  while (end > b * plan.block && !(end - 1 < n && plan.write[end - 1])) --end;
  return end;
}

bool frame_done(const fs::path& folder, int k) {
  return fs::exists(folder / frame_file_name(k, "png")) &&
         fs::exists(folder / frame_file_name(k, "svg"));
}

std::filesystem::path record_path(const fs::path& folder, int k) {
  return folder / ".stats" / frame_file_name(k, "json");
}

// Finished frames waiting for the writer besides the one it writes: one keeps it busy while the
// frame threads compute, more would only hold more pictures in memory.
constexpr std::size_t kWriterDepth = 1;

// The calling thread's CPU time in milliseconds: what writing costs, whatever else runs.
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

// Whether process `pid` still runs (a temporary's writer).
bool running(long pid) {
  return pid > 0 && (kill(pid_t(pid), 0) == 0 || errno == EPERM);
}

}  // namespace

FrameRange block_frames(int b, int block, int frame_count) {
  return {std::min(b * block, frame_count), std::min((b + 1) * block, frame_count)};
}

std::vector<FrameRange> block_aligned_ranges(int frame_count, int block, int parts) {
  block = std::max(1, block);
  const int blocks = (frame_count + block - 1) / block;
  parts = std::max(1, std::min(parts, blocks));
  std::vector<FrameRange> ranges;
  for (int i = 0, b = 0; i < parts; ++i) {
    const int count = blocks / parts + (i < blocks % parts ? 1 : 0);
    ranges.push_back({block_frames(b, block, frame_count).first,
                      block_frames(b + count - 1, block, frame_count).last});
    b += count;
  }
  return ranges;
}

std::string frame_file_name(int k, const char* ext) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%04d.%s", k, ext);
  return buf;
}

void check_frame_folder(const fs::path& folder) {
  std::error_code ec;
  if (fs::exists(folder, ec)) {
    if (!fs::is_directory(folder, ec))
      throw std::runtime_error(folder.string() + ": exists and is not a folder");
    if (access(folder.c_str(), W_OK) != 0)
      throw std::runtime_error(folder.string() + ": the output folder is not writable");
    return;
  }
  fs::path up = fs::absolute(folder, ec).parent_path();
  while (!up.empty() && !fs::exists(up, ec) && up != up.parent_path()) up = up.parent_path();
  if (!fs::is_directory(up, ec) || access(up.c_str(), W_OK) != 0)
    throw std::runtime_error(folder.string() + ": cannot create the output folder (" + up.string() +
                             " is not a writable folder)");
}

void prepare_frame_folder(const fs::path& folder, int first, int last) {
  std::error_code ec;
  fs::create_directories(folder / ".stats", ec);
  if (!fs::is_directory(folder / ".stats"))
    throw std::runtime_error(folder.string() + ": cannot create the output folder");
  // io::write_atomically's temporaries: ".frame_0005.partial-<pid>.png", ".preview.partial-..".
  const std::regex frame(R"(\.(frame|mask)_(\d+)\.partial-(\d+)\.(png|svg|json))");
  const std::regex other(R"(\.[a-z]+\.partial-(\d+)\.(mp4|png|json|svg))");
  for (const fs::path& dir : {folder, folder / ".stats"})
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      std::smatch m;
      const std::string name = entry.path().filename().string();
      const bool ours_to_redo =
          std::regex_match(name, m, frame) &&
          ((std::stoi(m[2]) >= first && (last < 0 || std::stoi(m[2]) < last)) ||
           !running(std::stol(m[3])));
      const bool orphan = std::regex_match(name, m, other) && !running(std::stol(m[1]));
      if (ours_to_redo || orphan) fs::remove(entry.path(), ec);
    }
}

double render_peak_bytes(int width, int height, int parallel) {
  return kRenderBaseBytes + kRenderBytesPerPixel * double(width) * height * parallel;
}

int RangePlan::write_count() const {
  return int(std::count(write.begin(), write.end(), 1));
}

RangePlan plan_range(const fs::path& folder, FrameRange range, int frame_count, int block,
                     bool force) {
  RangePlan plan;
  plan.block = std::max(1, block);
  plan.write.assign(frame_count, 0);
  for (int k = range.first; k < range.last; ++k) plan.write[k] = force || !frame_done(folder, k);
  for (int b = range.first / plan.block; b * plan.block < range.last; ++b) {
    bool any = false;
    const FrameRange in_block = block_frames(b, plan.block, frame_count);
    for (int k = std::max(range.first, in_block.first); k < std::min(range.last, in_block.last);
         ++k)
      any |= plan.write[k];
    if (any) plan.blocks.push_back(b);
  }
  return plan;
}

std::vector<nlohmann::json> render_range(const SceneFrames& frames, const FrameSetup& setup,
                                         const RangePlan& plan, const FrameFiles& files,
                                         const std::function<void(int count)>& written,
                                         const std::function<void()>& before_writing) {
  std::vector<nlohmann::json> stats(frames.frame_count());  // null: not written
  int count = 0;
  // Declared after what its jobs touch, so that an unwinding run stops it first. Its jobs run
  // one at a time: `stats`, `count` and `written` need no lock.
  FrameWriter writer(kWriterDepth);
  // The frames to compute in order: every frame of each planned block up to its last one to
  // write (the earlier ones only warm-start the later ones).
  std::vector<int> work;
  for (int b : plan.blocks)
    for (int k = b * plan.block; k < block_end(plan, b); ++k) work.push_back(k);
  // A frame in flight between the stages of render_frame.
  struct InFlight {
    int k = 0;
    Clock::time_point start;
    FrameResult r;
    std::shared_ptr<const FrameSolution> solved;  // the plain solve, until anti-aliased
  };
  // Frames overlap in a pipeline: the geometry of any frame may run while a frame is solved, and
  // the solves run one frame at a time in order, each warm-started by the frame before when both
  // are in the same block. So the frames of one block keep both cores busy (with blocks in
  // parallel, the last block ran alone on one), one solve is in flight at a time (one solver
  // workspace's memory instead of one per thread), and the pixels are those of a serial run.
  // Anti-aliasing needs no other frame: it leaves the serial stage, reading the plain solve that
  // it shares with the next frame's warm start (no copy).
  std::shared_ptr<const FrameSolution> warm;
  std::size_t next = 0;
  const std::size_t tokens = std::size_t(tbb::this_task_arena::max_concurrency()) + 1;
  using Frame = std::shared_ptr<InFlight>;
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& fc) -> std::size_t {
                                            if (next == work.size()) fc.stop();
                                            return next++;
                                          }) &
          tbb::make_filter<std::size_t, Frame>(
              tbb::filter_mode::parallel,
              [&](std::size_t i) {
                auto f = std::make_shared<InFlight>();
                const int k = f->k = work[i];
                // Frame k and its motion neighbour (the next one, for frame 0) may still be
                // simulated.
                frames.wait_for(k > 0 ? k : std::min(1, frames.frame_count() - 1));
                f->start = Clock::now();
                // Three independent parts: on a core that is free (the first frame), in parallel.
                // The occluders and the hair base share the eye rays against the head.
                BodyLayer body;
                std::vector<vector::Occluder> occluders;
                vector::HairBase base;
                tbb::this_task_arena::isolate([&] {
                  tbb::parallel_invoke([&] { body = frame_body(frames, k); },
                                       [&] {
                                         const auto head = frame_head_rays(frames, k);
                                         tbb::parallel_invoke(
                                             [&] { occluders = frame_occluders(frames, k, head); },
                                             [&] { base = frame_base(frames, k, head); });
                                       });
                });
                const double body_ms = ms_since(f->start);
                // Isolated: while a frame's parallel loops wait for a stolen part, the thread
                // must not start another frame's work nested inside (holding this one back).
                tbb::this_task_arena::isolate([&] {
                  f->r = render_geometry(frames.projected[k], std::move(body), std::move(occluders),
                                         std::move(base), setup);
                });
                f->r.time.body = body_ms;
                return f;
              }) &
          tbb::make_filter<Frame, Frame>(tbb::filter_mode::serial_in_order,
                                         [&](Frame f) {
                                           const int k = f->k;
                                           if (k % plan.block == 0) warm.reset();  // cold
                                           tbb::this_task_arena::isolate([&] {
                                             render_solve(f->r, frames.projected[k], setup,
                                                          warm.get(), motion_neighbour(frames, k));
                                           });
                                           f->solved = warm = std::make_shared<const FrameSolution>(
                                               std::move(f->r.solution));
                                           return f;
                                         }) &
          tbb::make_filter<Frame, Frame>(tbb::filter_mode::parallel,
                                         [&](Frame f) {
                                           // Solved only to warm-start the next frame: done.
                                           if (!plan.write[f->k]) return Frame();
                                           tbb::this_task_arena::isolate(
                                               [&] { render_finish(f->r, setup, *f->solved); });
                                           f->solved.reset();
                                           return f;
                                         }) &
          tbb::make_filter<Frame, void>(tbb::filter_mode::serial_in_order, [&](Frame f) {
            if (!f) return;
            const int k = f->k;
            FrameResult& r = f->r;
            nlohmann::json record = frame_stats(frames, k, r, 0, 0);
            auto picture = std::make_shared<FramePicture>(std::move(r.picture));
            const auto t_frame = f->start;
            f.reset();  // the arrangement, curves and constraints go before the next frame
            const auto t_wait = Clock::now();
            writer.wait_for_room();
            record["ms"]["write_wait"] = ms_since(t_wait);
            writer.push([&, k, t_frame, picture, record = std::move(record)]() mutable {
              if (count == 0 && before_writing) before_writing();
              const auto t_write = Clock::now();
              // The PNG and the SVG (each a PNG encode of its own) side by side: a core is often
              // free, always while the first frame is written. Isolated, so that this thread
              // waits for its own two writes only, never for a frame's work it might steal.
              double cpu[3] = {0, 0, 0};  // each write's CPU time, on whichever thread ran it
              auto timed = [](double& ms, auto&& write) {
                const double t0 = thread_cpu_ms();
                write();
                ms = thread_cpu_ms() - t0;
              };
              tbb::this_task_arena::isolate([&] {
                tbb::parallel_invoke(
                    [&] {
                      timed(cpu[0], [&] {
                        write_frame_png(*picture, files.folder / frame_file_name(k, "png"));
                      });
                    },
                    [&] {
                      timed(cpu[1], [&] {
                        write_frame_svg(*picture, files.folder / frame_file_name(k, "svg"),
                                        files.svg_style);
                      });
                    },
                    [&] {
                      if (!files.masks) return;
                      timed(cpu[2], [&] {
                        write_mask_png(
                            *picture,
                            files.folder / ("mask" + frame_file_name(k, "png").substr(5)));
                      });
                    });
              });
              picture.reset();
              record["ms"]["write"] = ms_since(t_write);
              record["ms"]["write_cpu"] = cpu[0] + cpu[1] + cpu[2];
              record["ms"]["frame"] = ms_since(t_frame);
              io::write_text_atomically(record_path(files.folder, k), record.dump() + "\n");
              stats[k] = std::move(record);
              if (written) written(++count);
            });
          }));
  writer.finish();
  // The frames are done: the previews that follow (the video encoder) need the memory.
  diffusion::release_solver_workspaces();
  std::vector<nlohmann::json> out;
  for (nlohmann::json& s : stats)
    if (!s.is_null()) out.push_back(std::move(s));
  return out;
}

std::vector<int> missing_frames(const fs::path& folder, FrameRange range) {
  std::vector<int> missing;
  for (int k = range.first; k < range.last; ++k)
    if (!frame_done(folder, k)) missing.push_back(k);
  return missing;
}

std::vector<nlohmann::json> range_records(const fs::path& folder, FrameRange range,
                                          const std::vector<nlohmann::json>& written) {
  std::vector<nlohmann::json> out;
  std::size_t next = 0;
  for (int k = range.first; k < range.last; ++k) {
    if (next < written.size() && written[next].value("frame", -1) == k) {
      out.push_back(written[next++]);
      continue;
    }
    std::ifstream in(record_path(folder, k));
    if (!in) continue;
    nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
    if (record.is_object()) out.push_back(std::move(record));
  }
  return out;
}

void write_previews(const io::Scene& scene, double fps, FrameRange range, const fs::path& folder) {
  std::vector<fs::path> pngs;
  std::vector<int> numbers;
  for (int k = range.first; k < range.last; ++k) {
    pngs.push_back(folder / frame_file_name(k, "png"));
    numbers.push_back(k);
  }
  io::ContactSheetOptions options;
  options.columns = scene.render.contact_sheet_columns;
  if (!scene.render.video) {
    io::write_contact_sheet(folder / "contact.png", pngs, numbers, options);
    return;
  }
  // Each frame read once, for both.
  io::ContactSheet sheet(folder / "contact.png", int(pngs.size()), numbers, options);
  io::write_video(folder / "preview.mp4", pngs, fps,
                  [&](int i, const io::RgbImage& frame) { sheet.add(frame, pngs[i]); });
  sheet.write();
}

SvgAnimationStats write_animated_svg(double fps, FrameRange range, const fs::path& folder) {
  std::vector<fs::path> svgs;
  for (int k = range.first; k < range.last; ++k) svgs.push_back(folder / frame_file_name(k, "svg"));
  return write_svg_animation(svgs, fps, folder / "animation.svg");
}

}  // namespace wisp::render
