// The contact sheet: every frame of a render downscaled into one PNG grid, row by row, each tile
// labelled with its frame number in the bottom-left corner (white digits on a dark box). Written
// atomically (io/atomic_file.hpp).
//
// Layout: tiles are `tile_width` pixels wide and as tall as the frames' aspect ratio makes them
// (rounded, at least 1), with `gap` pixels of background between tiles and around the sheet:
// width = cols * tile_w + (cols + 1) * gap, height = rows * tile_h + (rows + 1) * gap, where
// cols = min(columns, frames) and rows = ceil(frames / cols). Frames are scaled with area
// averaging (OpenCV INTER_AREA).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "io/png_decode.hpp"

namespace wisp::io {

struct ContactSheetOptions {
  int columns = 6;                                  // tiles per row, >= 1
  int tile_width = 192;                             // pixels, >= 8
  int gap = 4;                                      // pixels between and around tiles, >= 0
  bool labels = true;                               // draw the frame numbers
  Eigen::Vector3f background{0.15f, 0.15f, 0.15f};  // RGB in [0,1]
};

struct ContactSheetLayout {
  int columns = 0, rows = 0;
  int tile_width = 0, tile_height = 0;
  int width = 0, height = 0;  // of the sheet
};

// The layout for `count` frames of frame_width x frame_height pixels.
ContactSheetLayout contact_sheet_layout(int count, int frame_width, int frame_height,
                                        const ContactSheetOptions& options);

// The sheet of `count` frames, built a frame at a time and written at the end: for a caller that
// reads the frames anyway (the previews read each frame once for the video and the sheet).
class ContactSheet {
 public:
  // `numbers` as below. Throws std::runtime_error naming `path` for bad options, no frames or
  // numbers of the wrong length.
  ContactSheet(std::filesystem::path path, int count, std::vector<int> numbers,
               const ContactSheetOptions& options = {});
  // The next frame's tile; `source` names the frame in errors (a size other than the first's).
  void add(const RgbImage& frame, const std::filesystem::path& source);
  // Writes the sheet, once every frame was added; returns the layout.
  ContactSheetLayout write();

 private:
  std::filesystem::path path_;
  int count_ = 0, added_ = 0;
  std::vector<int> numbers_;
  ContactSheetOptions options_;
  int frame_width_ = 0, frame_height_ = 0;
  ContactSheetLayout layout_;
  std::vector<std::uint8_t> sheet_;  // RGB rows of layout_.width pixels
};

// Reads `frames` (PNG files, all the same size) and writes the sheet to `path`
// (.png). `numbers[i]` labels frames[i]; empty numbers label them 0, 1, 2... Returns the layout.
// Throws std::runtime_error naming the file: no frames, an unreadable frame or one of another
// size, numbers of the wrong length, bad options.
ContactSheetLayout write_contact_sheet(const std::filesystem::path& path,
                                       const std::vector<std::filesystem::path>& frames,
                                       const std::vector<int>& numbers,
                                       const ContactSheetOptions& options = {});

}  // namespace wisp::io
