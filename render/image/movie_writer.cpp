#include "render/image/movie_writer.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <new>
#include <vector>

#include "render/image/srgb8.hpp"

namespace tetray::render {
namespace {

// In order of preference; each goes into MP4.
constexpr const char* kCodecs[] = {"libx264", "libvpx-vp9", "mpeg4"};

const AVCodec* movie_codec() {
  for (const char* name : kCodecs) {
    if (const AVCodec* codec = avcodec_find_encoder_by_name(name)) return codec;
  }
  return nullptr;
}

std::string av_text(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = "";
  av_strerror(code, text, sizeof text);
  return text;
}

int even(int side) { return side + (side & 1); }

// The options that keep each frame's packet coming out of the encoder at once (no lookahead,
// no B-frames), so that it is on disk when append returns.
AVDictionary* encoder_options(const AVCodec* codec, const MovieOptions& options) {
  AVDictionary* dict = nullptr;
  if (std::strcmp(codec->name, "libx264") == 0) {
    av_dict_set(&dict, "preset", "veryfast", 0);
    av_dict_set(&dict, "tune", "zerolatency", 0);
    av_dict_set_int(&dict, "crf", options.quality, 0);
  } else if (std::strcmp(codec->name, "libvpx-vp9") == 0) {
    av_dict_set(&dict, "deadline", "realtime", 0);
    av_dict_set_int(&dict, "lag-in-frames", 0, 0);
    av_dict_set_int(&dict, "crf", options.quality, 0);
  }
  return dict;
}

// FFmpeg logs through one process-wide level, INFO by default, at which libx264 prints a dozen
// lines per movie. A host that chose a level keeps it; the default one becomes errors only.
void quiet_default_logging() {
  if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_ERROR);
}

// A directory where the movie is to go could not be replaced by it at close: said at create.
std::string replace_problem(const std::string& path) {
  struct stat found {};
  if (::lstat(path.c_str(), &found) != 0 || !S_ISDIR(found.st_mode)) return {};
  return "cannot create the file: " + std::string(std::strerror(EISDIR));
}

}  // namespace

std::string movie_codec_name() {
  const AVCodec* codec = movie_codec();
  return codec ? codec->name : "";
}

struct MovieWriter::State {
  std::string path;           // the name the movie takes once closed
  std::string temporary;      // the file written until then; empty once renamed
  int width = 0, height = 0;  // of the images; the frames have even sides
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* to_yuv = nullptr;
  std::vector<std::uint8_t> rgb;  // the padded frame, RGB24
  int frames = 0;
  bool closed = false;
  bool broken = false;  // a frame failed midway: the file may be torn, and is not kept

  // A movie never closed (or whose close failed) is abandoned: its temporary file goes.
  ~State() {
    sws_freeContext(to_yuv);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    discard();
    avformat_free_context(format);
  }

  void discard() {
    if (format && format->pb) avio_closep(&format->pb);
    if (!temporary.empty()) ::unlink(temporary.c_str());
    temporary.clear();
  }

  WriteResult failed(const std::string& what, int code) const {
    return {false, "movie '" + path + "': " + what + ": " + av_text(code)};
  }

  std::string open(const MovieOptions& options);
  WriteResult encode(const AVFrame* input);
  WriteResult finish();
  void pad_rgb(const Framebuffer& image);
};

std::string MovieWriter::State::open(const MovieOptions& options) {
  quiet_default_logging();
  const AVCodec* found = movie_codec();
  if (!found) return "FFmpeg's libavcodec offers none of libx264, libvpx-vp9, mpeg4";
  int rc = avformat_alloc_output_context2(&format, nullptr, "mp4", path.c_str());
  if (rc < 0) return "no MP4 muxer: " + av_text(rc);
  stream = avformat_new_stream(format, nullptr);
  codec = avcodec_alloc_context3(found);
  frame = av_frame_alloc();
  packet = av_packet_alloc();
  if (!stream || !codec || !frame || !packet) return "out of memory";
  codec->width = even(width);
  codec->height = even(height);
  codec->pix_fmt = AV_PIX_FMT_YUV420P;
  codec->time_base = {1, options.frames_per_second};
  codec->framerate = {options.frames_per_second, 1};
  codec->gop_size = options.frames_per_second;  // a key frame every second of the movie
  codec->max_b_frames = 0;
  codec->thread_count = options.threads;
  if (format->oformat->flags & AVFMT_GLOBALHEADER) codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* codec_options = encoder_options(found, options);
  rc = avcodec_open2(codec, found, &codec_options);
  av_dict_free(&codec_options);
  if (rc < 0) return std::string("cannot open the ") + found->name + " encoder: " + av_text(rc);
  if ((rc = avcodec_parameters_from_context(stream->codecpar, codec)) < 0) return av_text(rc);
  stream->time_base = codec->time_base;
  if (std::string problem = replace_problem(path); !problem.empty()) return problem;
  std::string error;
  temporary = create_temporary_file(path, error);
  if (temporary.empty()) return error;
  if ((rc = avio_open(&format->pb, temporary.c_str(), AVIO_FLAG_WRITE)) < 0) {
    return "cannot open '" + temporary + "': " + av_text(rc);
  }
  // Fragments where the caller flushes (after every frame), the index up front and each fragment
  // self-contained: every frame goes to the file as it comes, and the muxer keeps no index of
  // the whole movie in memory until close.
  format->flags |= AVFMT_FLAG_FLUSH_PACKETS;
  AVDictionary* muxer_options = nullptr;
  av_dict_set(&muxer_options, "movflags", "frag_custom+empty_moov+default_base_moof", 0);
  rc = avformat_write_header(format, &muxer_options);
  av_dict_free(&muxer_options);
  if (rc < 0) return "cannot write the header: " + av_text(rc);
  frame->format = codec->pix_fmt;
  frame->width = codec->width;
  frame->height = codec->height;
  if ((rc = av_frame_get_buffer(frame, 0)) < 0) return av_text(rc);
  to_yuv = sws_getContext(codec->width, codec->height, AV_PIX_FMT_RGB24, codec->width,
                          codec->height, AV_PIX_FMT_YUV420P, SWS_POINT, nullptr, nullptr, nullptr);
  if (!to_yuv) return "no RGB to YUV 4:2:0 conversion";
  rgb.resize(3 * static_cast<std::size_t>(codec->width) * codec->height);
  return {};
}

// Sends `input` (null: the end) and writes every packet the encoder gives back.
WriteResult MovieWriter::State::encode(const AVFrame* input) {
  int rc = avcodec_send_frame(codec, input);
  if (rc < 0) return failed("encoding", rc);
  while ((rc = avcodec_receive_packet(codec, packet)) >= 0) {
    // Each frame shows for one frame time; the muxer needs it for a fragment's last frame, which
    // it cannot take from the next frame's time stamp.
    packet->duration = 1;
    av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
    packet->stream_index = stream->index;
    rc = av_write_frame(format, packet);
    av_packet_unref(packet);
    if (rc < 0) return failed("writing", rc);
  }
  if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF) return failed("encoding", rc);
  return {};
}

// The image as RGB24 over black, its last column and row repeated up to the even frame size.
void MovieWriter::State::pad_rgb(const Framebuffer& image) {
  const std::vector<std::uint8_t> srgb = to_srgb8(image, Srgb8Alpha::over_black);
  const std::size_t in_row = 3 * static_cast<std::size_t>(width);
  const std::size_t out_row = 3 * static_cast<std::size_t>(codec->width);
  for (int j = 0; j < codec->height; ++j) {
    const std::uint8_t* from = &srgb[in_row * static_cast<std::size_t>(std::min(j, height - 1))];
    std::uint8_t* to = &rgb[out_row * static_cast<std::size_t>(j)];
    std::copy(from, from + in_row, to);
    if (codec->width != width) std::copy(from + in_row - 3, from + in_row, to + in_row);
  }
}

MovieWriter::MovieWriter(std::unique_ptr<State> state) : state_(std::move(state)) {}

MovieWriter::~MovieWriter() = default;

std::unique_ptr<MovieWriter> MovieWriter::create(const std::string& path, int width, int height,
                                                 const MovieOptions& options, std::string& error) {
  auto state = std::make_unique<State>();
  state->path = path;
  state->width = width;
  state->height = height;
  error = width > 0 && height > 0 ? state->open(options) : "empty frame size";
  if (!error.empty()) {
    error = "movie '" + path + "': " + error;
    return nullptr;
  }
  return std::unique_ptr<MovieWriter>(new MovieWriter(std::move(state)));
}

WriteResult MovieWriter::append(const Framebuffer& image) {
  State& s = *state_;
  if (s.closed) return {false, "movie '" + s.path + "': already closed"};
  if (s.broken) return {false, "movie '" + s.path + "': abandoned after a frame failed"};
  if (image.width != s.width || image.height != s.height) {
    return {false, "movie '" + s.path + "': a " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " image in a " + std::to_string(s.width) +
                       "x" + std::to_string(s.height) + " movie"};
  }
  try {
    s.pad_rgb(image);
  } catch (const std::bad_alloc&) {
    return {false, "movie '" + s.path + "': out of memory"};
  }
  int rc = av_frame_make_writable(s.frame);
  if (rc < 0) return s.failed("frame buffer", rc);
  const std::uint8_t* source[] = {s.rgb.data()};
  const int stride[] = {3 * s.codec->width};
  sws_scale(s.to_yuv, source, stride, 0, s.codec->height, s.frame->data, s.frame->linesize);
  s.frame->pts = s.frames;
  WriteResult sent = s.encode(s.frame);
  if (sent.ok && (rc = av_write_frame(s.format, nullptr)) < 0) {
    sent = s.failed("writing the fragment", rc);
  }
  s.broken = !sent.ok;
  if (sent.ok) ++s.frames;
  return sent;
}

// The end of the file written and closed, then the file renamed to the movie's name.
WriteResult MovieWriter::State::finish() {
  WriteResult result = encode(nullptr);
  if (const int rc = av_write_trailer(format); rc < 0 && result.ok) {
    result = failed("writing the end of the file", rc);
  }
  if (const int rc = avio_closep(&format->pb); rc < 0 && result.ok) {
    result = failed("closing", rc);
  }
  if (result.ok && ::rename(temporary.c_str(), path.c_str()) != 0) {
    result = {false, "movie '" + path + "': cannot rename '" + temporary +
                         "' to it: " + std::strerror(errno)};
  }
  if (result.ok) temporary.clear();
  return result;
}

WriteResult MovieWriter::close() {
  State& s = *state_;
  if (s.closed) return {};
  s.closed = true;
  WriteResult result = s.broken ? WriteResult{false, "movie '" + s.path +
                                                         "': not kept, a frame could not be "
                                                         "written"}
                                : s.finish();
  if (!result.ok) s.discard();
  return result;
}

int MovieWriter::frames() const { return state_->frames; }

const std::string& MovieWriter::path() const { return state_->path; }

}  // namespace tetray::render
