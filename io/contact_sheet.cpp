// write_contact_sheet: see contact_sheet.hpp. Frames are read and the sheet written with libpng
// (io/png_decode, io/png_encode); OpenCV only scales and draws, in RGB order.
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

ContactSheetLayout write_contact_sheet(const std::filesystem::path& path,
                                       const std::vector<std::filesystem::path>& frames,
                                       const std::vector<int>& numbers,
                                       const ContactSheetOptions& o) {
  const std::string file = path.string();
  if (path.extension() != ".png")
    throw std::runtime_error(file + ": the contact sheet must be a .png file");
  if (frames.empty()) throw std::runtime_error(file + ": no frames for the contact sheet");
  if (!numbers.empty() && numbers.size() != frames.size())
    throw std::runtime_error(file + ": " + std::to_string(numbers.size()) + " frame numbers for " +
                             std::to_string(frames.size()) + " frames");
  if (o.columns < 1 || o.tile_width < 8 || o.gap < 0 || o.tile_width > 8192 || o.gap > 1024)
    throw std::runtime_error(file + ": contact sheet options out of range");
  if (o.background.minCoeff() < 0 || o.background.maxCoeff() > 1)
    throw std::runtime_error(file + ": contact sheet background must be in [0, 1]");

  ContactSheetLayout l;
  cv::Mat sheet;
  cv::Size frame_size;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    RgbImage pixels;
    try {
      pixels = read_png(frames[i], "frame", kMaxImageSide);
    } catch (const std::runtime_error&) {
      throw std::runtime_error(file + ": cannot read the frame " + frames[i].string());
    }
    const cv::Mat image(pixels.height, pixels.width, CV_8UC3, pixels.pixels.data());
    if (i == 0) {
      frame_size = image.size();
      l = contact_sheet_layout(static_cast<int>(frames.size()), image.cols, image.rows, o);
      const auto channel = [](float v) { return std::lround(v * 255.0f); };
      sheet = cv::Mat(l.height, l.width, CV_8UC3,
                      cv::Scalar(channel(o.background.x()), channel(o.background.y()),
                                 channel(o.background.z())));
    } else if (image.size() != frame_size) {
      throw std::runtime_error(file + ": the frame " + frames[i].string() +
                               " differs in size from the first frame");
    }
    const int col = static_cast<int>(i) % l.columns, row = static_cast<int>(i) / l.columns;
    const cv::Rect tile(o.gap + col * (l.tile_width + o.gap), o.gap + row * (l.tile_height + o.gap),
                        l.tile_width, l.tile_height);
    cv::Mat target = sheet(tile);
    cv::resize(image, target, tile.size(), 0, 0, cv::INTER_AREA);
    if (o.labels) {
      const std::string text = std::to_string(numbers.empty() ? int(i) : numbers[i]);
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
                  cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), thickness,
                  cv::LINE_AA);
    }
  }
  write_png_fast(path, {sheet.data, sheet.cols, sheet.rows, 3, sheet.step[0]});
  return l;
}

}  // namespace wisp::io
