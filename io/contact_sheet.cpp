// ContactSheet and write_contact_sheet: see contact_sheet.hpp. Frames are read and the sheet
// written with libpng (io/png_decode, io/png_encode); OpenCV only scales and draws, in RGB order.
#include "io/contact_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "io/drawing_xml.hpp"
#include "io/png_decode.hpp"
#include "io/png_encode.hpp"

namespace wisp::io {

ContactSheetLayout contact_sheet_layout(int count, int frame_width, int frame_height,
                                        const ContactSheetOptions& o) {
  ContactSheetLayout l;
  if (count <= 0 || frame_width <= 0 || frame_height <= 0) return l;
  l.columns = std::min(o.columns, count);
  l.rows = (count + l.columns - 1) / l.columns;
  l.tile_width = o.tile_width;
  l.tile_height =
      std::max(1, static_cast<int>(std::lround(double(o.tile_width) * frame_height / frame_width)));
  l.width = l.columns * l.tile_width + (l.columns + 1) * o.gap;
  l.height = l.rows * l.tile_height + (l.rows + 1) * o.gap;
  return l;
}

ContactSheet::ContactSheet(std::filesystem::path path, int count, std::vector<int> numbers,
                           const ContactSheetOptions& o)
    : path_(std::move(path)), count_(count), numbers_(std::move(numbers)), options_(o) {
  const std::string file = path_.string();
  if (path_.extension() != ".png")
    throw std::runtime_error(file + ": the contact sheet must be a .png file");
  if (count <= 0) throw std::runtime_error(file + ": no frames for the contact sheet");
  if (!numbers_.empty() && numbers_.size() != std::size_t(count))
    throw std::runtime_error(file + ": " + std::to_string(numbers_.size()) + " frame numbers for " +
                             std::to_string(count) + " frames");
  if (o.columns < 1 || o.tile_width < 8 || o.gap < 0 || o.tile_width > 8192 || o.gap > 1024)
    throw std::runtime_error(file + ": contact sheet options out of range");
  if (o.background.minCoeff() < 0 || o.background.maxCoeff() > 1)
    throw std::runtime_error(file + ": contact sheet background must be in [0, 1]");
}

void ContactSheet::add(const RgbImage& pixels, const std::filesystem::path& source) {
  const std::string file = path_.string();
  const ContactSheetOptions& o = options_;
  const int i = added_;
  if (i >= count_) throw std::runtime_error(file + ": more frames than the sheet was made for");
  const cv::Mat image(pixels.height, pixels.width, CV_8UC3,
                      const_cast<std::uint8_t*>(pixels.pixels.data()));
  if (i == 0) {
    frame_width_ = image.cols, frame_height_ = image.rows;
    layout_ = contact_sheet_layout(count_, image.cols, image.rows, o);
    const auto channel = [](float v) { return std::uint8_t(std::lround(v * 255.0f)); };
    const std::uint8_t background[3] = {channel(o.background.x()), channel(o.background.y()),
                                        channel(o.background.z())};
    sheet_.resize(std::size_t(layout_.width) * layout_.height * 3);
    for (std::size_t k = 0; k < sheet_.size(); ++k) sheet_[k] = background[k % 3];
  } else if (image.cols != frame_width_ || image.rows != frame_height_) {
    throw std::runtime_error(file + ": the frame " + source.string() +
                             " differs in size from the first frame");
  }
  const ContactSheetLayout& l = layout_;
  const int col = i % l.columns, row = i / l.columns;
  const cv::Rect tile(o.gap + col * (l.tile_width + o.gap), o.gap + row * (l.tile_height + o.gap),
                      l.tile_width, l.tile_height);
  cv::Mat target = cv::Mat(l.height, l.width, CV_8UC3, sheet_.data())(tile);
  cv::resize(image, target, tile.size(), 0, 0, cv::INTER_AREA);
  if (o.labels) {
    const std::string text = std::to_string(numbers_.empty() ? i : numbers_[std::size_t(i)]);
    const double scale = std::clamp(l.tile_width / 320.0, 0.3, 1.5);
    const int thickness = 1;
    int baseline = 0;
    const cv::Size ts =
        cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline);
    const int pad = 2;
    // Drawn into the tile's view of the sheet: OpenCV clips to it, so a long label on a tiny
    // tile never spills into its neighbours.
    const int box_h = ts.height + baseline + 2 * pad;
    cv::rectangle(target, cv::Rect(0, l.tile_height - box_h, ts.width + 2 * pad, box_h),
                  cv::Scalar(0, 0, 0), cv::FILLED);
    cv::putText(target, text, cv::Point(pad, l.tile_height - baseline - pad),
                cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), thickness, cv::LINE_AA);
  }
  ++added_;
}

ContactSheetLayout ContactSheet::write() {
  if (added_ != count_)
    throw std::runtime_error(path_.string() + ": " + std::to_string(added_) + " of " +
                             std::to_string(count_) + " frames were added to the contact sheet");
  write_png_fast(path_,
                 {sheet_.data(), layout_.width, layout_.height, 3, std::size_t(layout_.width) * 3});
  return layout_;
}

ContactSheetLayout write_contact_sheet(const std::filesystem::path& path,
                                       const std::vector<std::filesystem::path>& frames,
                                       const std::vector<int>& numbers,
                                       const ContactSheetOptions& o) {
  ContactSheet sheet(path, int(frames.size()), numbers, o);
  for (const std::filesystem::path& frame : frames) {
    RgbImage pixels;
    try {
      pixels = read_png(frame, "frame", kMaxImageSide);
    } catch (const std::runtime_error&) {
      throw std::runtime_error(path.string() + ": cannot read the frame " + frame.string());
    }
    sheet.add(pixels, frame);
  }
  return sheet.write();
}

}  // namespace wisp::io
