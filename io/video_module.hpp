// The boundary between io/video_file and the video module, wisp-video.so: the few calls into
// FFmpeg (libavformat, libavcodec, libswscale) that writing and checking a preview needs, as plain
// C functions. FFmpeg brings some 130 shared libraries (codecs, x264), so it is loaded (dlopen)
// only when a video is written or checked, not by every command at start-up
// (docs/performance.md). The module is built from io/video_module.cpp alone and installed in
// lib/wisp/ beside the bin/ folder of the executables (util/module.hpp).
#pragma once

extern "C" {

// Opens an MP4 writer for width x height frames at `fps` with the four-letter codec `fourcc`
// ("avc1": H.264 through x264; "mp4v": MPEG-4 part 2); null when FFmpeg cannot. Odd sides lose
// their last column or row.
void* wisp_video_open(const char* path, const char* fourcc, double fps, int width, int height);

// Appends one frame: width x height x 3 bytes, RGB, rows without padding. 0 on failure.
int wisp_video_write(void* writer, const unsigned char* rgb);

// Finishes the file and frees the writer.
void wisp_video_close(void* writer);

// Decodes the whole video and counts its frames; -1 if it cannot be opened.
int wisp_video_count_frames(const char* path);

}  // extern "C"
