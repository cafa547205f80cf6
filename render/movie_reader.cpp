#include "render/movie_reader.h"

#include <new>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include "render/av_error.h"
#include "sim/error.h"

namespace gs::render {

struct MovieReader::Av {
  AVFormatContext* fmt = nullptr;
  AVCodecContext* dec = nullptr;
  AVPacket* pkt = nullptr;
  AVFrame* frame = nullptr;
  int stream = -1;
  ~Av() {
    av_frame_free(&frame);
    av_packet_free(&pkt);
    avcodec_free_context(&dec);
    avformat_close_input(&fmt);
  }
};

MovieReader::MovieReader(const std::filesystem::path& path)
    : path_(path), av_(std::make_unique<Av>()) {
  // Every failure reaches the user through check_av; libav's own log lines would only repeat
  // them and break the one-line messages.
  if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_FATAL);
  check_av(avformat_open_input(&av_->fmt, path.c_str(), nullptr, nullptr), path, "cannot open");
  check_av(avformat_find_stream_info(av_->fmt, nullptr), path, "cannot read the streams");
  const AVCodec* codec = nullptr;
  av_->stream = av_find_best_stream(av_->fmt, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  check_av(av_->stream, path, "no video stream");
  const AVStream* st = av_->fmt->streams[av_->stream];
  const AVCodecParameters* par = st->codecpar;
  info_.codec_id = par->codec_id;
  info_.width = par->width;
  info_.height = par->height;
  // libavformat takes any file named .png or .jpg for a one-picture "movie" by its name alone; a
  // text file so named has a stream of no size.
  if (info_.width <= 0 || info_.height <= 0)
    throw UserError("movie '" + path.string() + "': its video stream has no picture size " +
                    "(libavformat read it as " + av_->fmt->iformat->name + ")");
  info_.avg_rate_num = st->avg_frame_rate.num, info_.avg_rate_den = st->avg_frame_rate.den;
  info_.r_rate_num = st->r_frame_rate.num, info_.r_rate_den = st->r_frame_rate.den;
  if (av_->fmt->duration != AV_NOPTS_VALUE)
    info_.duration = double(av_->fmt->duration) / AV_TIME_BASE;
  info_.nb_frames = st->nb_frames;
  info_.color_range = par->color_range;
  info_.color_space = par->color_space;
  info_.color_primaries = par->color_primaries;
  info_.color_trc = par->color_trc;
  av_->dec = avcodec_alloc_context3(codec);
  av_->pkt = av_packet_alloc();
  av_->frame = av_frame_alloc();
  if (!av_->dec || !av_->pkt || !av_->frame) throw std::bad_alloc();
  check_av(avcodec_parameters_to_context(av_->dec, par), path, "decoder parameters");
  check_av(avcodec_open2(av_->dec, codec, nullptr), path, "cannot open the decoder");
}

MovieReader::~MovieReader() = default;

bool MovieReader::next() {
  const std::string where = "frame " + std::to_string(frames_);
  for (;;) {
    av_frame_unref(av_->frame);
    const int got = avcodec_receive_frame(av_->dec, av_->frame);
    if (got == 0) {
      ++frames_;
      return true;
    }
    if (got == AVERROR_EOF) return false;
    if (got != AVERROR(EAGAIN)) check_av(got, path_, where.c_str());
    if (flushed_) return false;
    // The decoder wants input: the next packet of our stream, or the flush at the end.
    int read;
    while ((read = av_read_frame(av_->fmt, av_->pkt)) >= 0 && av_->pkt->stream_index != av_->stream)
      av_packet_unref(av_->pkt);
    if (read < 0 && read != AVERROR_EOF) check_av(read, path_, where.c_str());
    if (read < 0) {
      flushed_ = true;
      check_av(avcodec_send_packet(av_->dec, nullptr), path_, where.c_str());
    } else {
      const int sent = avcodec_send_packet(av_->dec, av_->pkt);
      av_packet_unref(av_->pkt);
      check_av(sent, path_, where.c_str());
    }
  }
}

Image MovieReader::rgb() const {
  const AVFrame* f = av_->frame;
  GS_CHECK(frames_ > 0 && f->width > 0);
  Image out(f->width, f->height);
  SwsContext* sws = sws_getContext(
      f->width, f->height, AVPixelFormat(f->format), f->width, f->height, AV_PIX_FMT_RGBA,
      SWS_BILINEAR | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr, nullptr, nullptr);
  if (!sws) throw UserError("movie '" + path_.string() + "': cannot convert its pixel format");
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  sws_setColorspaceDetails(sws, bt709, 0, bt709, 1, 0, 1 << 16, 1 << 16);
  std::uint8_t* dst[1] = {out.rgba.data()};
  const int stride[1] = {f->width * 4};
  sws_scale(sws, f->data, f->linesize, 0, f->height, dst, stride);
  sws_freeContext(sws);
  return out;
}

int MovieReader::luma(int x, int y) const {
  const AVFrame* f = av_->frame;
  GS_CHECK(frames_ > 0 && x >= 0 && y >= 0 && x < f->width && y < f->height);
  return f->data[0][y * f->linesize[0] + x];
}

}  // namespace gs::render
