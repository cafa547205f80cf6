#include "tests/render/movie_decode.h"

#include <gtest/gtest.h>

#include <cmath>

extern "C" {
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

namespace gs::render {

double psnr(const Image& a, const Image& b, int w, int h) {
  double sum = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.pixel(x, y)[c]) - double(b.pixel(x, y)[c]);
        sum += d * d;
      }
  const double mse = sum / (3.0 * w * h);
  return mse == 0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}

Decoded decode_movie(const std::filesystem::path& path, int keep) {
  Decoded out;
  AVFormatContext* fmt = nullptr;
  if (avformat_open_input(&fmt, path.c_str(), nullptr, nullptr) < 0) {
    ADD_FAILURE() << "cannot open " << path;
    return out;
  }
  EXPECT_GE(avformat_find_stream_info(fmt, nullptr), 0);
  const AVCodec* codec = nullptr;
  const int si = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  EXPECT_GE(si, 0);
  if (si < 0) {
    avformat_close_input(&fmt);
    return out;
  }
  const AVStream* st = fmt->streams[si];
  out.codec = st->codecpar->codec_id;
  out.width = st->codecpar->width;
  out.height = st->codecpar->height;
  out.avg_frame_rate = st->avg_frame_rate;
  out.r_frame_rate = st->r_frame_rate;
  out.duration = fmt->duration == AV_NOPTS_VALUE ? -1 : double(fmt->duration) / AV_TIME_BASE;
  out.nb_frames = st->nb_frames;
  out.range = st->codecpar->color_range;
  out.space = st->codecpar->color_space;
  out.primaries = st->codecpar->color_primaries;
  out.trc = st->codecpar->color_trc;

  AVCodecContext* dec = avcodec_alloc_context3(codec);
  EXPECT_GE(avcodec_parameters_to_context(dec, st->codecpar), 0);
  EXPECT_GE(avcodec_open2(dec, codec, nullptr), 0);
  AVPacket* pkt = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  auto take = [&] {
    if (out.frames == keep) {
      out.rgb = Image(frame->width, frame->height);
      SwsContext* sws = sws_getContext(frame->width, frame->height, AVPixelFormat(frame->format),
                                       frame->width, frame->height, AV_PIX_FMT_RGBA,
                                       SWS_BILINEAR | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT,
                                       nullptr, nullptr, nullptr);
      const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
      EXPECT_GE(sws_setColorspaceDetails(sws, bt709, 0, bt709, 1, 0, 1 << 16, 1 << 16), 0);
      std::uint8_t* dst[1] = {out.rgb.rgba.data()};
      const int stride[1] = {frame->width * 4};
      sws_scale(sws, frame->data, frame->linesize, 0, frame->height, dst, stride);
      sws_freeContext(sws);
    }
    out.centre_luma.push_back(
        frame->data[0][(frame->height / 2) * frame->linesize[0] + frame->width / 2]);
    ++out.frames;
  };
  auto drain = [&] {
    while (avcodec_receive_frame(dec, frame) == 0) {
      take();
      av_frame_unref(frame);
    }
  };
  while (av_read_frame(fmt, pkt) >= 0) {
    if (pkt->stream_index == si) {
      EXPECT_GE(avcodec_send_packet(dec, pkt), 0);
      drain();
    }
    av_packet_unref(pkt);
  }
  EXPECT_GE(avcodec_send_packet(dec, nullptr), 0);
  drain();
  av_frame_free(&frame);
  av_packet_free(&pkt);
  avcodec_free_context(&dec);
  avformat_close_input(&fmt);
  return out;
}

}  // namespace gs::render
