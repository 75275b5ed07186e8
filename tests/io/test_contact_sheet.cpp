// The contact sheet: its size, each tile's content and label, errors.

#include <catch2/catch.hpp>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "io/contact_sheet.hpp"
#include "io/png_decode.hpp"
#include "tests/test_folder.hpp"

namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
  return wisp::test::test_folder("contact_sheet");
}

// A flat colour per frame: frame i is (40 + 20 i, 200 - 15 i, 30 + 7 i) in BGR.
cv::Vec3b colour(int i) {
  return cv::Vec3b(40 + 20 * i, 200 - 15 * i, 30 + 7 * i);
}

std::vector<fs::path> flat_frames(const fs::path& dir, int count, int w, int h) {
  std::vector<fs::path> frames;
  for (int i = 0; i < count; ++i) {
    const cv::Mat m(h, w, CV_8UC3, cv::Scalar(colour(i)[0], colour(i)[1], colour(i)[2]));
    frames.push_back(dir / ("f" + std::to_string(i) + ".png"));
    REQUIRE(cv::imwrite(frames.back().string(), m));
  }
  return frames;
}

}  // namespace

TEST_CASE("contact sheet: grid size, tile content and frame numbers", "[io][contact]") {
  const fs::path dir = temp_dir();
  const std::vector<fs::path> frames = flat_frames(dir, 7, 320, 240);
  wisp::io::ContactSheetOptions options;
  options.columns = 3;
  options.tile_width = 96;
  options.gap = 4;
  const fs::path sheet_path = dir / "contact.png";
  const wisp::io::ContactSheetLayout l =
      wisp::io::write_contact_sheet(sheet_path, frames, {10, 11, 12, 13, 14, 15, 16}, options);
  CHECK(l.columns == 3);
  CHECK(l.rows == 3);
  CHECK(l.tile_width == 96);
  CHECK(l.tile_height == 72);
  CHECK(l.width == 3 * 96 + 4 * 4);
  CHECK(l.height == 3 * 72 + 4 * 4);
  const cv::Mat sheet = cv::imread(sheet_path.string());
  REQUIRE(!sheet.empty());
  CHECK(sheet.cols == l.width);
  CHECK(sheet.rows == l.height);
  const cv::Vec3b background(38, 38, 38);  // 0.15 * 255, rounded
  for (int i = 0; i < 9; ++i) {
    const int x0 = 4 + (i % 3) * 100, y0 = 4 + (i / 3) * 76;
    INFO("tile " << i);
    if (i < 7) {
      // The top half of a tile is the frame's colour; the bottom-left corner holds the label,
      // dark box and white digits.
      CHECK(sheet.at<cv::Vec3b>(y0 + 10, x0 + 48) == colour(i));
      CHECK(sheet.at<cv::Vec3b>(y0 + 5, x0 + 90) == colour(i));
      int white = 0, black = 0;
      for (int y = y0 + 50; y < y0 + 72; ++y)
        for (int x = x0; x < x0 + 30; ++x) {
          const cv::Vec3b p = sheet.at<cv::Vec3b>(y, x);
          white += p[0] > 200 && p[1] > 200 && p[2] > 200;
          black += p == cv::Vec3b(0, 0, 0);
        }
      CHECK(white > 5);
      CHECK(black > 20);
    } else {
      CHECK(sheet.at<cv::Vec3b>(y0 + 36, x0 + 48) == background);  // empty slots
    }
  }
  CHECK(sheet.at<cv::Vec3b>(1, 1) == background);  // the gap around the tiles

  // Without labels every tile pixel is the frame's colour; numbers default to 0, 1, 2...
  options.labels = false;
  options.columns = 10;
  const wisp::io::ContactSheetLayout one_row =
      wisp::io::write_contact_sheet(sheet_path, frames, {}, options);
  CHECK(one_row.columns == 7);
  CHECK(one_row.rows == 1);
  const cv::Mat plain = cv::imread(sheet_path.string());
  CHECK(plain.at<cv::Vec3b>(4 + 71, 4 + 6 * 100) == colour(6));
  fs::remove_all(dir);
}

TEST_CASE("contact sheet errors name the file", "[io][contact]") {
  const fs::path dir = temp_dir();
  const std::vector<fs::path> frames = flat_frames(dir, 2, 32, 32);
  CHECK_THROWS_WITH(wisp::io::write_contact_sheet(dir / "c.jpg", frames, {}),
                    Catch::Contains(".png"));
  CHECK_THROWS_WITH(wisp::io::write_contact_sheet(dir / "c.png", {}, {}),
                    Catch::Contains("no frames"));
  CHECK_THROWS_WITH(wisp::io::write_contact_sheet(dir / "c.png", frames, {1}),
                    Catch::Contains("1 frame numbers for 2 frames"));
  CHECK_THROWS_WITH(wisp::io::write_contact_sheet(dir / "c.png", {frames[0], dir / "gone.png"}, {}),
                    Catch::Contains("gone.png"));
  CHECK_THROWS_WITH(wisp::io::write_contact_sheet(dir / "missing" / "c.png", frames, {}),
                    Catch::Contains("does not exist"));
  CHECK(!fs::exists(dir / "c.png"));
  fs::remove_all(dir);
}

TEST_CASE("a contact sheet built a frame at a time is write_contact_sheet's", "[io][contact]") {
  // The previews hand the video's frames to a ContactSheet as they are read.
  const fs::path dir = temp_dir();
  const std::vector<fs::path> frames = flat_frames(dir, 4, 64, 48);
  const wisp::io::ContactSheetLayout whole =
      wisp::io::write_contact_sheet(dir / "whole.png", frames, {5, 6, 7, 8});
  wisp::io::ContactSheet sheet(dir / "built.png", 4, {5, 6, 7, 8});
  for (const fs::path& f : frames) sheet.add(wisp::io::read_png(f, "frame", 4096), f);
  CHECK_THROWS_WITH(sheet.add(wisp::io::read_png(frames[0], "frame", 4096), frames[0]),
                    Catch::Contains("more frames"));
  const wisp::io::ContactSheetLayout built = sheet.write();
  CHECK(built.width == whole.width);
  CHECK(built.height == whole.height);
  const cv::Mat a = cv::imread((dir / "whole.png").string()),
                b = cv::imread((dir / "built.png").string());
  REQUIRE(!a.empty());
  CHECK(cv::norm(a, b, cv::NORM_INF) == 0);

  // A frame of another size names itself; a sheet missing frames is not written.
  fs::create_directories(dir / "other");
  const std::vector<fs::path> other = flat_frames(dir / "other", 1, 32, 32);
  wisp::io::ContactSheet short_sheet(dir / "short.png", 3, {});
  short_sheet.add(wisp::io::read_png(frames[0], "frame", 4096), frames[0]);
  CHECK_THROWS_WITH(short_sheet.add(wisp::io::read_png(other[0], "frame", 4096), other[0]),
                    Catch::Contains(other[0].string()));
  CHECK_THROWS_WITH(short_sheet.write(), Catch::Contains("1 of 3 frames"));
  CHECK(!fs::exists(dir / "short.png"));
  fs::remove_all(dir);
}
