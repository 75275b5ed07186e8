// io/png_decode against OpenCV's imread(IMREAD_COLOR), which read ramps, contact-sheet frames and
// video frames before: the same RGB pixels for every kind of PNG OpenCV writes.
#include <catch2/catch.hpp>
#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "io/png_decode.hpp"

namespace {

// A pattern with every byte value in each channel, in `type` (8 or 16 bits, 1, 3 or 4 channels).
cv::Mat pattern(int type) {
  cv::Mat m(37, 53, type);
  const double scale = CV_MAT_DEPTH(type) == CV_16U ? 257.3 : 1.0;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      for (int c = 0; c < m.channels(); ++c) {
        const int v = (x * 7 + y * 13 + c * 61) % 256;
        if (CV_MAT_DEPTH(type) == CV_16U)
          m.ptr<std::uint16_t>(y)[x * m.channels() + c] = std::uint16_t(v * scale);
        else
          m.ptr<std::uint8_t>(y)[x * m.channels() + c] = std::uint8_t(v);
      }
  return m;
}

}  // namespace

TEST_CASE("PNG decoding gives imread's pixels for grey, RGB, alpha, 16-bit and 1-bit images",
          "[io][png]") {
  const struct {
    const char* name;
    cv::Mat image;
    std::vector<int> params;
  } cases[] = {{"grey", pattern(CV_8UC1), {}},
               {"grey 16-bit", pattern(CV_16UC1), {}},
               {"RGB", pattern(CV_8UC3), {}},
               {"RGBA", pattern(CV_8UC4), {}},
               {"RGB 16-bit", pattern(CV_16UC3), {}},
               {"RGBA 16-bit", pattern(CV_16UC4), {}},
               {"1-bit", pattern(CV_8UC1) > 128, {cv::IMWRITE_PNG_BILEVEL, 1}}};
  for (const auto& c : cases) {
    INFO(c.name);
    std::vector<std::uint8_t> bytes;
    REQUIRE(cv::imencode(".png", c.image, bytes, c.params));
    cv::Mat expected = cv::imdecode(bytes, cv::IMREAD_COLOR);
    cv::cvtColor(expected, expected, cv::COLOR_BGR2RGB);
    const wisp::io::RgbImage got = wisp::io::decode_png(bytes.data(), bytes.size(), 4096);
    REQUIRE(got.width == expected.cols);
    REQUIRE(got.height == expected.rows);
    CHECK(std::equal(got.pixels.begin(), got.pixels.end(), expected.data));
  }
}

TEST_CASE("PNG decoding refuses truncated, foreign and oversized images", "[io][png]") {
  std::vector<std::uint8_t> bytes;
  REQUIRE(cv::imencode(".png", pattern(CV_8UC3), bytes));
  const std::vector<std::uint8_t> half(bytes.begin(), bytes.begin() + bytes.size() / 2);
  CHECK_THROWS_WITH(wisp::io::decode_png(half.data(), half.size(), 4096),
                    Catch::Contains("cannot decode the PNG image"));
  const std::uint8_t text[] = "GIF89a, not a PNG";
  CHECK_THROWS_WITH(wisp::io::decode_png(text, sizeof text, 4096),
                    Catch::Equals("not a PNG image"));
  CHECK_THROWS_WITH(wisp::io::decode_png(bytes.data(), bytes.size(), 40),
                    Catch::Contains("cannot decode the PNG image"));  // 53 px wide
}
