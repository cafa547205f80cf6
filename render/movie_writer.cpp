#include "render/movie_writer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <system_error>
#include <utility>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
}

#include "render/av_error.h"
#include "render/yuv420.h"
#include "sim/error.h"

namespace gs::render {

namespace {

std::string shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

int round_up_even(int n) {
  return n + (n & 1);
}

// Copies `src` into `dst` (even size, at least one larger), repeating the last column and row.
// Repeating rather than padding with black keeps the border chroma sample the colour of the edge.
void pad_replicate(const Image& src, Image& dst) {
  const std::size_t row = static_cast<std::size_t>(src.width) * 4;
  for (int y = 0; y < dst.height; ++y) {
    const std::uint8_t* s = src.pixel(0, std::min(y, src.height - 1));
    std::uint8_t* d = dst.pixel(0, y);
    std::memcpy(d, s, row);
    for (int x = src.width; x < dst.width; ++x) std::memcpy(d + x * 4, s + row - 4, 4);
  }
}

// The encoder for a codec name: libx264 for "h264" and "libx264", with "h264" falling back to
// MPEG-4 Part 2 when libavcodec was built without libx264. Null if unavailable or unknown.
const AVCodec* find_encoder(const std::string& name) {
  if (name == "h264" || name == "libx264") {
    if (const AVCodec* c = avcodec_find_encoder_by_name("libx264")) return c;
    return name == "h264" ? avcodec_find_encoder(AV_CODEC_ID_MPEG4) : nullptr;
  }
  if (name == "mpeg4") return avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  return nullptr;
}

}  // namespace

// Each of these is a flag's value (movie's and run's), so a usage error that names the flag.
void check_movie_options(const MovieOptions& o) {
  if (o.codec != "h264" && o.codec != "libx264" && o.codec != "mpeg4")
    throw UsageError("unknown --codec '" + o.codec + "' (use h264, libx264 or mpeg4)");
  if (o.width <= 0 || o.height <= 0)
    throw UsageError("movie frame size " + std::to_string(o.width) + "x" +
                     std::to_string(o.height) + " (--width, --height) must be positive");
  if (!(o.fps > 0) || !std::isfinite(o.fps) || o.fps > 1000)
    throw UsageError("--fps " + shortest(o.fps) + ": must be in (0, 1000]");
  if (o.crf < 0 || o.crf > 51)
    throw UsageError("--crf " + std::to_string(o.crf) + ": must be in 0..51");
  if (o.keyint < 1 || o.keyint > 100000)
    throw UsageError("--keyint " + std::to_string(o.keyint) + ": must be in 1..100000");
  if (o.queue_frames < 1) throw UserError("movie queue_frames must be >= 1");
}

struct MovieWriter::Av {
  AVFormatContext* format = nullptr;
  AVCodecContext* encoder = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  Image padded;
  std::int64_t next_pts = 0;

  ~Av() {
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&encoder);
    if (format) {
      if (format->pb) avio_closep(&format->pb);  // error path only: the result is discarded anyway
      avformat_free_context(format);
    }
  }
};

MovieWriter::MovieWriter(const std::filesystem::path& path, const MovieOptions& options)
    : path_(path), options_(options), uncaught_at_construction_(std::uncaught_exceptions()) {
  const MovieOptions& o = options_;
  const std::string name = path_.string();
  check_movie_options(o);
  const AVCodec* codec = find_encoder(o.codec);
  if (!codec)
    throw UserError("movie '" + name + "': codec '" + o.codec + "' is not in this libavcodec");
  encoder_name_ = codec->name;
  const bool x264 = encoder_name_ == "libx264";

  const AVOutputFormat* container = av_guess_format(nullptr, path_.filename().c_str(), nullptr);
  if (!container)
    throw UserError("movie '" + name +
                    "': cannot tell the container from the file name (use .mp4)");
  if (avformat_query_codec(container, codec->id, FF_COMPLIANCE_NORMAL) != 1)
    throw UserError("movie '" + name + "': container '" + container->name + "' cannot hold " +
                    encoder_name_);

  // The muxer reopens the file by name for +faststart, so libav works on the temporary name only.
  const auto folder = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  // Hidden, and unique per process so that two writers aimed at one name cannot mix their bytes.
  std::string temp_name = ".";  // appended piecewise: GCC 12 warns falsely on "." + string
  temp_name += path_.filename().string();
  temp_name += "." + std::to_string(getpid()) + ".partial";
  temp_path_ = folder / temp_name;

  encoded_width_ = round_up_even(o.width);
  encoded_height_ = round_up_even(o.height);

  // libx264 prints encoding statistics at info level, which mean nothing to our users; a program
  // that raised or lowered the level on purpose keeps its choice.
  if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_ERROR);

  av_ = std::make_unique<Av>();
  try {
    Av& av = *av_;
    check_av(avformat_alloc_output_context2(&av.format, container, nullptr, temp_path_.c_str()),
             path_, "cannot set up the container");

    av.encoder = avcodec_alloc_context3(codec);
    GS_CHECK(av.encoder);
    AVCodecContext* enc = av.encoder;
    const AVRational rate = av_d2q(o.fps, 65535);  // MPEG-4 Part 2 allows 16-bit time bases only
    enc->width = encoded_width_;
    enc->height = encoded_height_;
    enc->framerate = rate;
    enc->time_base = av_inv_q(rate);
    enc->sample_aspect_ratio = AVRational{1, 1};
    enc->pix_fmt = AV_PIX_FMT_YUV420P;
    enc->color_range = AVCOL_RANGE_MPEG;
    enc->colorspace = AVCOL_SPC_BT709;
    enc->color_primaries = AVCOL_PRI_BT709;
    enc->color_trc = AVCOL_TRC_BT709;
    enc->thread_count = o.threads;
    if (av.format->oformat->flags & AVFMT_GLOBALHEADER) enc->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;

    AVDictionary* codec_opts = nullptr;
    if (x264) {
      GS_CHECK(av_dict_set(&codec_opts, "preset", o.preset.c_str(), 0) >= 0);
      GS_CHECK(av_dict_set(&codec_opts, "crf", std::to_string(o.crf).c_str(), 0) >= 0);
    } else {
      enc->flags |= AV_CODEC_FLAG_QSCALE;
      enc->global_quality = FF_QP2LAMBDA * std::max(1, (o.crf + 3) / 6);
      enc->gop_size = std::max(1, static_cast<int>(std::lround(2 * o.fps)));
    }
    const int opened = avcodec_open2(enc, codec, &codec_opts);
    const int unused_opts = av_dict_count(codec_opts);
    av_dict_free(&codec_opts);
    check_av(opened, path_,
             (std::string("cannot open encoder ") + encoder_name_ +
              (x264 ? " with preset '" + o.preset + "'" : std::string()))
                 .c_str());
    GS_CHECK_MSG(unused_opts == 0, "encoder ignored an option");

    av.stream = avformat_new_stream(av.format, nullptr);
    GS_CHECK(av.stream);
    check_av(avcodec_parameters_from_context(av.stream->codecpar, enc), path_,
             "cannot describe the stream");
    av.stream->time_base = enc->time_base;
    av.stream->avg_frame_rate = rate;

    check_av(avio_open(&av.format->pb, temp_path_.c_str(), AVIO_FLAG_WRITE), path_,
             "cannot write to the folder");
    AVDictionary* mux_opts = nullptr;
    // The index goes to the front so that players and browsers can start before the download ends.
    if (av_opt_find(av.format->priv_data, "movflags", nullptr, 0, 0))
      GS_CHECK(av_dict_set(&mux_opts, "movflags", "+faststart", 0) >= 0);
    const int header = avformat_write_header(av.format, &mux_opts);
    const int unused_mux = av_dict_count(mux_opts);
    av_dict_free(&mux_opts);
    check_av(header, path_, "cannot write the header");
    GS_CHECK_MSG(unused_mux == 0, "muxer ignored an option");

    av.frame = av_frame_alloc();
    GS_CHECK(av.frame);
    av.frame->format = AV_PIX_FMT_YUV420P;
    av.frame->width = encoded_width_;
    av.frame->height = encoded_height_;
    av.frame->color_range = enc->color_range;
    av.frame->colorspace = enc->colorspace;
    av.frame->color_primaries = enc->color_primaries;
    av.frame->color_trc = enc->color_trc;
    GS_CHECK(av_frame_get_buffer(av.frame, 0) >= 0);
    av.packet = av_packet_alloc();
    GS_CHECK(av.packet);
    if (encoded_width_ != o.width || encoded_height_ != o.height)
      av.padded = Image(encoded_width_, encoded_height_);

    worker_ = std::thread([this] { worker_loop(); });
  } catch (...) {
    av_.reset();
    remove_partial();
    throw;
  }
}

MovieWriter::~MovieWriter() {
  if (std::uncaught_exceptions() > uncaught_at_construction_) {
    discard();
    return;
  }
  try {
    finish();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainshock: error: %s\n", e.what());
  }
}

void MovieWriter::add(Image frame) {
  GS_CHECK_MSG(!done_, "frame added to a finished movie");
  GS_CHECK(frame.width == options_.width && frame.height == options_.height);
  GS_CHECK(frame.rgba.size() == static_cast<std::size_t>(frame.width) * frame.height * 4);
  std::unique_lock lock(mutex_);
  cv_.wait(lock,
           [&] { return static_cast<int>(queue_.size()) < options_.queue_frames || worker_done_; });
  if (worker_done_) {  // before closing_, the worker only stops on an error
    lock.unlock();
    finish();  // rethrows the worker's error
    GS_CHECK_MSG(false, "movie worker stopped without an error");
  }
  queue_.push_back(std::move(frame));
  ++frames_added_;
  lock.unlock();
  cv_.notify_all();
}

Image MovieWriter::spare() {
  std::lock_guard lock(mutex_);
  return std::exchange(spare_, Image{});
}

void MovieWriter::finish() {
  if (done_) return;
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  cv_.notify_all();
  stop_worker();
  if (worker_error_) {
    remove_partial();
    std::rethrow_exception(worker_error_);
  }
  std::error_code ec;
  std::filesystem::rename(temp_path_, path_, ec);
  if (ec) {
    remove_partial();
    throw UserError("movie '" + path_.string() +
                    "': cannot move the finished file into place: " + ec.message());
  }
}

void MovieWriter::discard() {
  if (done_) return;
  {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
  }
  cv_.notify_all();
  stop_worker();
  remove_partial();
}

void MovieWriter::stop_worker() {
  if (worker_.joinable()) worker_.join();
  done_ = true;
  av_.reset();  // closes the file if the worker did not
}

void MovieWriter::remove_partial() noexcept {
  std::error_code ec;
  std::filesystem::remove(temp_path_, ec);
}

void MovieWriter::worker_loop() {
  try {
    for (;;) {
      Image frame;
      {
        std::unique_lock lock(mutex_);
        cv_.wait(lock, [&] { return !queue_.empty() || closing_ || cancelled_; });
        if (cancelled_) break;
        if (queue_.empty()) break;  // closing and drained
        frame = std::move(queue_.front());
        queue_.pop_front();
      }
      cv_.notify_all();
      encode_frame(frame);
      std::lock_guard lock(mutex_);
      spare_ = std::move(frame);
    }
    bool cancelled;
    {
      std::lock_guard lock(mutex_);
      cancelled = cancelled_;
    }
    if (!cancelled) {
      Av& av = *av_;
      encode_frame(Image());  // flush
      check_av(av_write_trailer(av.format), path_, "cannot write the trailer");
      check_av(avio_closep(&av.format->pb), path_, "cannot close the file");
    }
  } catch (...) {
    std::lock_guard lock(mutex_);
    worker_error_ = std::current_exception();
  }
  {
    std::lock_guard lock(mutex_);
    worker_done_ = true;
  }
  cv_.notify_all();
}

// An empty image flushes the encoder.
void MovieWriter::encode_frame(const Image& image) {
  Av& av = *av_;
  AVFrame* frame = nullptr;
  if (!image.rgba.empty()) {
    const Image* src = &image;
    if (!av.padded.rgba.empty()) {
      pad_replicate(image, av.padded);
      src = &av.padded;
    }
    // The encoder may still hold a reference to the previous picture.
    GS_CHECK(av_frame_make_writable(av.frame) >= 0);
    // RGB is full range; the movie is BT.709 limited range, matching the tags set above.
    GS_CHECK(av.frame->linesize[1] == av.frame->linesize[2]);
    rgba_to_yuv420(*src, av.frame->data[0], av.frame->linesize[0], av.frame->data[1],
                   av.frame->data[2], av.frame->linesize[1]);
    av.frame->pts = av.next_pts++;
    frame = av.frame;
  }
  check_av(avcodec_send_frame(av.encoder, frame), path_, "cannot encode a frame");
  for (;;) {
    const int ret = avcodec_receive_packet(av.encoder, av.packet);
    if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) break;
    check_av(ret, path_, "cannot encode a frame");
    if (av.packet->duration == 0) av.packet->duration = 1;  // one frame, in the encoder's time base
    av_packet_rescale_ts(av.packet, av.encoder->time_base, av.stream->time_base);
    av.packet->stream_index = av.stream->index;
    check_av(av_interleaved_write_frame(av.format, av.packet), path_, "cannot write a frame");
  }
}

}  // namespace gs::render
