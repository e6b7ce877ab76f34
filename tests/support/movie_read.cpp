#include "support/movie_read.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

namespace tetray::testing {

DecodedMovie decode_movie(const std::string& path) {
  DecodedMovie movie;
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) {
    movie.error = "cannot open " + path;
    return movie;
  }
  avformat_find_stream_info(format, nullptr);
  const AVCodec* decoder = nullptr;
  const int stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (stream < 0 || !decoder) {
    movie.error = "no video stream";
    avformat_close_input(&format);
    return movie;
  }
  AVCodecContext* codec = avcodec_alloc_context3(decoder);
  avcodec_parameters_to_context(codec, format->streams[stream]->codecpar);
  avcodec_open2(codec, decoder, nullptr);
  movie.codec = decoder->name;
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  const auto receive = [&] {
    while (avcodec_receive_frame(codec, frame) >= 0) {
      if (movie.frames++ == 0) {
        movie.width = frame->width;
        movie.height = frame->height;
        for (int j = 0; j < frame->height; ++j) {
          const std::uint8_t* row = frame->data[0] + j * frame->linesize[0];
          movie.first_luma.insert(movie.first_luma.end(), row, row + frame->width);
        }
      }
    }
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == stream) avcodec_send_packet(codec, packet);
    av_packet_unref(packet);
    receive();
  }
  avcodec_send_packet(codec, nullptr);
  receive();
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&codec);
  avformat_close_input(&format);
  return movie;
}

}  // namespace tetray::testing
