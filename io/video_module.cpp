// The video module (see video_module.hpp): OpenCV's VideoWriter and VideoCapture behind a C
// boundary. Nothing here throws across it: OpenCV's exceptions become a null writer or 0.
#include "io/video_module.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

namespace {

struct Writer {
  cv::VideoWriter video;
  cv::Size size;
};

}  // namespace

extern "C" {

void* wisp_video_open(const char* path, const char* fourcc, double fps, int width, int height) {
  try {
    auto* w = new Writer{cv::VideoWriter(), cv::Size(width, height)};
    if (w->video.open(path, cv::CAP_FFMPEG,
                      cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]), fps,
                      w->size, true))
      return w;
    delete w;
  } catch (const cv::Exception&) {
  }
  return nullptr;
}

int wisp_video_write(void* writer, const unsigned char* rgb) {
  auto* w = static_cast<Writer*>(writer);
  try {
    const cv::Mat frame(w->size, CV_8UC3, const_cast<unsigned char*>(rgb));
    cv::Mat bgr;
    cv::cvtColor(frame, bgr, cv::COLOR_RGB2BGR);
    w->video.write(bgr);
    return 1;
  } catch (const cv::Exception&) {
    return 0;
  }
}

void wisp_video_close(void* writer) {
  auto* w = static_cast<Writer*>(writer);
  try {
    w->video.release();
  } catch (const cv::Exception&) {
  }
  delete w;
}

int wisp_video_count_frames(const char* path) {
  try {
    cv::VideoCapture capture(path, cv::CAP_FFMPEG);
    if (!capture.isOpened()) return -1;
    int count = 0;
    cv::Mat frame;
    while (capture.read(frame)) ++count;
    return count;
  } catch (const cv::Exception&) {
    return -1;
  }
}

}  // extern "C"
