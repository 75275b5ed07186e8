// A range of frames rendered into a folder, resumably (see render_range.hpp).
#include "apps/render/render_range.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <regex>
#include <stdexcept>

#include "apps/render/render_stats.hpp"
#include "diffusion/timer.hpp"
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

void prepare_frame_folder(const fs::path& folder, int first, int last) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder))
    throw std::runtime_error(folder.string() + ": cannot create the output folder");
  // io::write_atomically's temporaries: ".frame_0005.partial-<pid>.png".
  const std::regex temporary(R"(\.(frame|mask)_(\d+)\.partial-\d+\.(png|svg))");
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, m, temporary) && std::stoi(m[2]) >= first &&
        (last < 0 || std::stoi(m[2]) < last))
      fs::remove(entry.path(), ec);
  }
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
                                         const std::function<void(int count)>& written) {
  std::vector<nlohmann::json> stats(frames.frame_count());  // null: not written
  std::mutex mutex;
  int count = 0;
  tbb::parallel_for(size_t(0), plan.blocks.size(), [&](size_t bi) {
    const int b = plan.blocks[bi];
    const int end = block_end(plan, b);
    std::vector<float> warm;
    for (int k = b * plan.block; k < end; ++k) {
      const auto t_frame = Clock::now();
      FrameResult r =
          render_frame(frames.projected[k], frame_body(frames, k), frame_occluders(frames, k),
                       frame_base(frames, k), setup, warm.empty() ? nullptr : &warm);
      warm = std::move(r.solution);
      if (!plan.write[k]) continue;  // solved only to warm-start the next frame of the block
      const auto t_write = Clock::now();
      write_frame_png(r.picture, files.folder / frame_file_name(k, "png"));
      write_frame_svg(r.picture, files.folder / frame_file_name(k, "svg"), files.svg_style);
      if (files.masks)
        write_mask_png(r.picture.mask, r.picture.width, r.picture.height,
                       files.folder / ("mask" + frame_file_name(k, "png").substr(5)));
      const double write_ms = ms_since(t_write);
      stats[k] = frame_stats(frames, k, r, write_ms, ms_since(t_frame));
      std::lock_guard<std::mutex> lock(mutex);
      if (written) written(++count);
    }
  });
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

void write_previews(const io::Scene& scene, double fps, FrameRange range, const fs::path& folder) {
  std::vector<fs::path> pngs;
  std::vector<int> numbers;
  for (int k = range.first; k < range.last; ++k) {
    pngs.push_back(folder / frame_file_name(k, "png"));
    numbers.push_back(k);
  }
  if (scene.render.video) io::write_video(folder / "preview.mp4", pngs, fps);
  io::ContactSheetOptions sheet;
  sheet.columns = scene.render.contact_sheet_columns;
  io::write_contact_sheet(folder / "contact.png", pngs, numbers, sheet);
}

}  // namespace wisp::render
