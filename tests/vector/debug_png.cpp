// OpenCV drawing of arrangements and rasters for visual inspection.
#include "tests/vector/debug_png.hpp"

#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace wisp::test {

namespace {

cv::Scalar colour(int label) {
  if (label < 0) return {0, 0, 0};
  const unsigned h = unsigned(label) * 2654435761u;
  return {double(60 + (h & 0x7f)), double(60 + ((h >> 8) & 0x7f)), double(60 + ((h >> 16) & 0x7f))};
}

std::vector<cv::Point> to_cv(const std::vector<Eigen::Vector2d>& ring, int scale) {
  std::vector<cv::Point> out;
  // Fixed-point with 4 fractional bits for sub-pixel drawing.
  for (const auto& p : ring) out.emplace_back(int(p.x() * scale * 16), int(p.y() * scale * 16));
  return out;
}

}  // namespace

std::string debug_png_dir() {
  const char* dir = std::getenv("WISP_DEBUG_PNG");
  return dir ? dir : "";
}

void write_arrangement_png(const std::string& path, const vector::ArrangementView& view, int width,
                           int height, int scale) {
  cv::Mat img(height * scale, width * scale, CV_8UC3, cv::Scalar(30, 30, 30));
  for (const auto& f : view.faces) {
    if (f.unbounded || f.front < 0) continue;
    std::vector<std::vector<cv::Point>> rings = {to_cv(f.outer, scale)};
    for (const auto& h : f.holes) rings.push_back(to_cv(h, scale));
    cv::fillPoly(img, rings, colour(f.front), cv::LINE_8, 4);
  }
  for (const auto& e : view.edges) {
    bool vis = false, frame = false;
    for (const auto& s : e.sources) vis |= s.visible, frame |= s.wisp < 0;
    const cv::Scalar c = vis     ? cv::Scalar(255, 255, 255)
                         : frame ? cv::Scalar(200, 120, 0)
                                 : cv::Scalar(0, 0, 140);
    cv::line(img, cv::Point(int(e.a.x() * scale * 16), int(e.a.y() * scale * 16)),
             cv::Point(int(e.b.x() * scale * 16), int(e.b.y() * scale * 16)), c, 1, cv::LINE_AA, 4);
  }
  for (const auto& v : view.vertices)
    if (v.intersection)
      cv::circle(img, cv::Point(int(v.p.x() * scale * 16), int(v.p.y() * scale * 16)), 2 * 16,
                 cv::Scalar(0, 220, 255), -1, cv::LINE_AA, 4);
  cv::imwrite(path, img);
}

void write_raster_png(const std::string& path, const Raster& r) {
  cv::Mat img(r.height, r.width, CV_8UC3);
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) {
      const cv::Scalar c = colour(r.at(x, y));
      img.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(c[0]), uchar(c[1]), uchar(c[2]));
    }
  cv::imwrite(path, img);
}

void write_diff_png(const std::string& path, const Raster& a, const Raster& b) {
  cv::Mat img(a.height, a.width, CV_8UC3);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const cv::Scalar c = colour(a.at(x, y)) * 0.4;
      img.at<cv::Vec3b>(y, x) = a.at(x, y) != b.at(x, y)
                                    ? cv::Vec3b(255, 255, 255)
                                    : cv::Vec3b(uchar(c[0]), uchar(c[1]), uchar(c[2]));
    }
  cv::imwrite(path, img);
}

}  // namespace wisp::test
