// The video module (see video_module.hpp): FFmpeg's libraries called directly, so that the
// encoder's settings are ours. Nothing here throws across the C boundary: a failure is a null
// writer, 0 or -1.
//
// Same frames, same bytes. x264 runs without its AVX-512 code: on CPUs that have it, x264 0.164's
// mbtree_propagate_list_avx512 propagates macroblock-tree costs eight macroblocks at a time past
// the end of a macroblock row (widths that are not a multiple of 128 pixels), reading costs x264
// never wrote (those of non-reference B frames past the first row, the padding after the last),
// so the bitstream depended on what the heap held before: two encodes of the same frames in one
// process differed (docs/output.md, "The preview video"). Without AVX-512 the bytes are those of
// the AVX2 code, the same as on CPUs without AVX-512 and as AVX-512's when nothing is misread;
// encoding costs the same. Should x264's CPU detection not be found, the macroblock tree is
// turned off instead (deterministic too, but about 30 % larger files). The thread count is fixed,
// since x264's output depends on it. Odd sides lose their last column or row (4:2:0 needs even
// ones), as OpenCV's writer, used before, did; a side of 1 pixel is refused.
#include "io/video_module.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <dlfcn.h>
#include <link.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace {

// x264's frame threads: fixed, so that every machine writes the same bytes.
constexpr int kEncoderThreads = 2;

// A preview, not a master: "veryfast" takes half the CPU of x264's default "medium" for 0.5 dB
// of PSNR and 1-2 % more bytes (docs/output.md, "The preview video").
constexpr const char* kX264Preset = "veryfast";

// X264_CPU_AVX512 of x264.h (not installed with the library).
constexpr std::uint32_t kX264CpuAvx512 = 1u << 16;

// x264_cpu_detect of the libx264 that libavcodec loaded with this module; null if none is.
using CpuDetect = std::uint32_t (*)();
CpuDetect find_x264_cpu_detect() {
  void* found = nullptr;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* out) -> int {
        const char* slash = std::strrchr(info->dlpi_name, '/');
        const char* name = slash ? slash + 1 : info->dlpi_name;
        if (std::strncmp(name, "libx264.so", 10) != 0) return 0;
        if (void* lib = dlopen(info->dlpi_name, RTLD_LAZY | RTLD_NOLOAD))
          *static_cast<void**>(out) = dlsym(lib, "x264_cpu_detect");
        return 1;
      },
      &found);
  return reinterpret_cast<CpuDetect>(found);
}

// The x264 settings under which the bytes depend on the frames alone (see the top of this file).
const std::string& x264_params() {
  static const std::string params = [] {
    const CpuDetect detect = find_x264_cpu_detect();
    return detect ? "asm=" + std::to_string(detect() & ~kX264CpuAvx512) : std::string("mbtree=0");
  }();
  return params;
}

struct Writer {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  SwsContext* to_yuv = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  int width = 0;  // the input frames' row length in pixels (the encoded width may be one less)
  int64_t next_pts = 0;
  bool header_written = false;
  // The frame's rows as sws_scale reads them: its SIMD loads read up to 16 bytes past the last
  // pixel (valgrind: 4 past a 256x256 frame's end, a page boundary for an mmapped buffer).
  std::vector<std::uint8_t> padded;

  ~Writer() {
    av_packet_free(&packet);
    av_frame_free(&frame);
    sws_freeContext(to_yuv);
    avcodec_free_context(&codec);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
  }
};

// Hands `frame` (null: the end) to the encoder and writes the packets it gives back.
bool encode(Writer& w, const AVFrame* frame) {
  if (avcodec_send_frame(w.codec, frame) < 0) return false;
  for (;;) {
    const int got = avcodec_receive_packet(w.codec, w.packet);
    if (got == AVERROR(EAGAIN) || got == AVERROR_EOF) return true;
    if (got < 0) return false;
    // One frame long (the encoder leaves it 0): without it the muxer's edit list ends at the last
    // frame's start, and decoders drop that frame.
    if (w.packet->duration == 0) w.packet->duration = 1;
    av_packet_rescale_ts(w.packet, w.codec->time_base, w.stream->time_base);
    w.packet->stream_index = w.stream->index;
    if (av_interleaved_write_frame(w.format, w.packet) < 0) return false;
  }
}

// The encoder of a fourcc: H.264 through x264 ("avc1") or MPEG-4 part 2 ("mp4v").
const AVCodec* find_encoder(const std::string& fourcc) {
  if (fourcc == "avc1") return avcodec_find_encoder_by_name("libx264");
  if (fourcc == "mp4v") return avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  return nullptr;
}

bool open_writer(Writer& w, const char* path, const char* fourcc, double fps, int width,
                 int height) {
  const AVCodec* encoder = find_encoder(fourcc);
  const int coded_width = width & ~1, coded_height = height & ~1;
  if (!encoder || coded_width <= 0 || coded_height <= 0 || !(fps > 0)) return false;
  w.width = width;
  if (avformat_alloc_output_context2(&w.format, nullptr, "mp4", path) < 0) return false;
  w.stream = avformat_new_stream(w.format, nullptr);
  w.codec = avcodec_alloc_context3(encoder);
  if (!w.stream || !w.codec) return false;
  const AVRational rate = av_d2q(fps, 65535);  // MPEG-4 part 2 takes denominators < 2^16
  w.codec->width = coded_width;
  w.codec->height = coded_height;
  w.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  w.codec->time_base = av_inv_q(rate);
  w.codec->framerate = rate;
  w.codec->thread_count = kEncoderThreads;
  if (w.format->oformat->flags & AVFMT_GLOBALHEADER) w.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (std::strcmp(fourcc, "avc1") == 0) {
    av_opt_set(w.codec->priv_data, "x264-params", x264_params().c_str(), 0);
    av_opt_set(w.codec->priv_data, "preset", kX264Preset, 0);
  } else {
    w.codec->flags |= AV_CODEC_FLAG_QSCALE;  // a constant quality, as good as x264's default
    w.codec->global_quality = 3 * FF_QP2LAMBDA;
  }
  if (avcodec_open2(w.codec, encoder, nullptr) < 0) return false;
  if (avcodec_parameters_from_context(w.stream->codecpar, w.codec) < 0) return false;
  w.stream->time_base = w.codec->time_base;
  w.frame = av_frame_alloc();
  w.packet = av_packet_alloc();
  if (!w.frame || !w.packet) return false;
  w.frame->format = w.codec->pix_fmt;
  w.frame->width = coded_width;
  w.frame->height = coded_height;
  if (av_frame_get_buffer(w.frame, 0) < 0) return false;
  w.to_yuv = sws_getContext(coded_width, coded_height, AV_PIX_FMT_RGB24, coded_width, coded_height,
                            AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (!w.to_yuv) return false;
  if (avio_open(&w.format->pb, path, AVIO_FLAG_WRITE) < 0) return false;
  // No creation time or other metadata that differs between runs is written.
  if (avformat_write_header(w.format, nullptr) < 0) return false;
  w.header_written = true;
  return true;
}

}  // namespace

extern "C" {

void* wisp_video_open(const char* path, const char* fourcc, double fps, int width, int height) {
  av_log_set_level(AV_LOG_QUIET);  // failures are reported by the caller, naming the file
  auto* w = new Writer;
  if (open_writer(*w, path, fourcc, fps, width, height)) return w;
  delete w;
  return nullptr;
}

int wisp_video_write(void* writer, const unsigned char* rgb) {
  auto* w = static_cast<Writer*>(writer);
  if (av_frame_make_writable(w->frame) < 0) return 0;
  const int stride[1] = {3 * w->width};
  const std::size_t bytes = std::size_t(stride[0]) * std::size_t(w->codec->height);
  w->padded.resize(bytes + AV_INPUT_BUFFER_PADDING_SIZE);
  std::memcpy(w->padded.data(), rgb, bytes);
  const uint8_t* rows[1] = {w->padded.data()};
  sws_scale(w->to_yuv, rows, stride, 0, w->codec->height, w->frame->data, w->frame->linesize);
  w->frame->pts = w->next_pts++;
  return encode(*w, w->frame) ? 1 : 0;
}

void wisp_video_close(void* writer) {
  auto* w = static_cast<Writer*>(writer);
  if (w->header_written && encode(*w, nullptr)) av_write_trailer(w->format);
  delete w;
}

int wisp_video_count_frames(const char* path) {
  av_log_set_level(AV_LOG_QUIET);
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path, nullptr, nullptr) < 0) return -1;
  int count = -1;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  const int index = avformat_find_stream_info(format, nullptr) < 0
                        ? -1
                        : av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  const AVCodec* decoder =
      index < 0 ? nullptr : avcodec_find_decoder(format->streams[index]->codecpar->codec_id);
  if (decoder && packet && frame && (codec = avcodec_alloc_context3(decoder)) &&
      avcodec_parameters_to_context(codec, format->streams[index]->codecpar) >= 0 &&
      avcodec_open2(codec, decoder, nullptr) >= 0) {
    // Every frame decoded, the ones the decoder holds back until the end included.
    count = 0;
    bool ok = true;
    const auto drain = [&] {
      for (int got; (got = avcodec_receive_frame(codec, frame)) >= 0;) ++count;
    };
    while (ok && av_read_frame(format, packet) >= 0) {
      if (packet->stream_index == index) ok = avcodec_send_packet(codec, packet) >= 0;
      av_packet_unref(packet);
      drain();
    }
    if (ok && avcodec_send_packet(codec, nullptr) >= 0) drain();
    if (!ok) count = -1;
  }
  avcodec_free_context(&codec);
  av_frame_free(&frame);
  av_packet_free(&packet);
  avformat_close_input(&format);
  return count;
}

}  // extern "C"
