// The boundary between io/video_file and the video module, wisp-video.so: the few calls into
// OpenCV's videoio that writing and checking a preview needs, as plain C functions. videoio
// brings FFmpeg, GStreamer and some 240 shared libraries, so it is loaded (dlopen) only when a
// video is written or checked, not by every command at start-up (docs/performance.md). The module
// is built from io/video_module.cpp alone and installed in lib/wisp/ beside the bin/ folder of
// the executables (io/install_layout.hpp).
#pragma once

extern "C" {

// Opens an MP4 writer (FFmpeg back end) for width x height frames at `fps` with the four-letter
// codec `fourcc`; null when OpenCV cannot.
void* wisp_video_open(const char* path, const char* fourcc, double fps, int width, int height);

// Appends one frame: width x height x 3 bytes, RGB, rows without padding. 0 on failure.
int wisp_video_write(void* writer, const unsigned char* rgb);

// Finishes the file and frees the writer.
void wisp_video_close(void* writer);

// Decodes the whole video and counts its frames; -1 if it cannot be opened.
int wisp_video_count_frames(const char* path);

}  // extern "C"
