#include "render/movie_parts.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
}

#include "render/av_error.h"
#include "sim/error.h"

namespace gs::render {

namespace fs = std::filesystem;

namespace {

struct Input {
  AVFormatContext* f = nullptr;
  ~Input() { avformat_close_input(&f); }
};

struct Output {
  AVFormatContext* f = nullptr;
  ~Output() {
    if (!f) return;
    if (f->pb) avio_closep(&f->pb);
    avformat_free_context(f);
  }
};

struct Packet {
  AVPacket* p = av_packet_alloc();
  ~Packet() { av_packet_free(&p); }
};

// The one video stream of a part; UserError naming it otherwise.
const AVStream* open_part(Input& in, const fs::path& part) {
  check_av(avformat_open_input(&in.f, part.c_str(), nullptr, nullptr), part, "cannot open");
  check_av(avformat_find_stream_info(in.f, nullptr), part, "cannot read the stream");
  if (in.f->nb_streams != 1 || in.f->streams[0]->codecpar->codec_type != AVMEDIA_TYPE_VIDEO)
    throw UserError("movie '" + part.string() + "': not a movie of one video stream");
  return in.f->streams[0];
}

bool same_stream(const AVStream* a, const AVStream* b) {
  const AVCodecParameters *p = a->codecpar, *q = b->codecpar;
  return p->codec_id == q->codec_id && p->width == q->width && p->height == q->height &&
         p->format == q->format && av_cmp_q(a->time_base, b->time_base) == 0 &&
         p->extradata_size == q->extradata_size &&
         (p->extradata_size == 0 ||
          std::memcmp(p->extradata, q->extradata, p->extradata_size) == 0);
}

// fdatasync of a whole file, so that a checkpoint never names a part the disk does not hold.
void sync_file(const fs::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
  const bool ok = fd >= 0 && ::fdatasync(fd) == 0;
  const int err = errno;
  if (fd >= 0) ::close(fd);
  if (!ok)
    throw UserError("movie '" + p.string() + "': cannot sync to disk: " + std::strerror(err));
}

// How long before its first frame is shown a part starts decoding, in its time base: a part
// long enough for B-frames does (its first decode times are negative), a short one does not.
std::int64_t decode_lead(Input& in, const fs::path& part) {
  Packet pkt;
  GS_CHECK(pkt.p);
  check_av(av_read_frame(in.f, pkt.p), part, "cannot read a frame");
  const std::int64_t dts = pkt.p->dts;
  return dts == AV_NOPTS_VALUE ? 0 : std::max<std::int64_t>(0, -dts);
}

}  // namespace

void join_movies(const std::vector<fs::path>& parts, const fs::path& out) {
  GS_CHECK(!parts.empty());
  Input first;
  const AVStream* model = open_part(first, parts.front());
  // Every part is checked, and its lead read, before anything is written.
  std::vector<std::int64_t> lead(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    Input in;
    const AVStream* s = open_part(in, parts[i]);
    if (!same_stream(s, model))
      throw UserError("movie '" + parts[i].string() + "' was encoded otherwise than '" +
                      parts.front().string() + "': the parts of one movie share their settings");
    lead[i] = decode_lead(in, parts[i]);
  }
  const std::int64_t max_lead = *std::max_element(lead.begin(), lead.end());

  std::string tmp_name = ".";  // appended piecewise: GCC 12 warns falsely on "." + string
  tmp_name += out.filename().string();
  tmp_name += '.';
  tmp_name += std::to_string(getpid());
  tmp_name += ".partial";
  const fs::path tmp = (out.has_parent_path() ? out.parent_path() : fs::path(".")) / tmp_name;
  Output o;
  const AVOutputFormat* container = av_guess_format(nullptr, out.filename().c_str(), nullptr);
  if (!container)
    throw UserError("movie '" + out.string() + "': cannot tell the container from the file name");
  check_av(avformat_alloc_output_context2(&o.f, container, nullptr, tmp.c_str()), out,
           "cannot set up the container");
  AVStream* st = avformat_new_stream(o.f, nullptr);
  GS_CHECK(st);
  check_av(avcodec_parameters_copy(st->codecpar, model->codecpar), out, "cannot copy the stream");
  st->codecpar->codec_tag = 0;
  st->time_base = model->time_base;
  st->avg_frame_rate = model->avg_frame_rate;
  st->sample_aspect_ratio = model->sample_aspect_ratio;
  auto remove_tmp = [&] {
    std::error_code ec;
    fs::remove(tmp, ec);
  };
  try {
    check_av(avio_open(&o.f->pb, tmp.c_str(), AVIO_FLAG_WRITE), out, "cannot write to the folder");
    AVDictionary* mux = nullptr;
    if (av_opt_find(o.f->priv_data, "movflags", nullptr, 0, 0))
      GS_CHECK(av_dict_set(&mux, "movflags", "+faststart", 0) >= 0);
    const int header = avformat_write_header(o.f, &mux);
    av_dict_free(&mux);
    check_av(header, out, "cannot write the header");

    // The parts' own shown times start at 0; shifting each by where the one before ended keeps
    // frame k at k / fps. Decode times are shifted by as much, less the lead the part lacks:
    // every part then decodes as far ahead of its frames as the longest one, and decode times
    // rise across the joins.
    std::int64_t offset = 0, last_dts = AV_NOPTS_VALUE;
    Packet pkt;
    GS_CHECK(pkt.p);
    for (std::size_t i = 0; i < parts.size(); ++i) {
      Input in;
      const AVStream* s = open_part(in, parts[i]);
      std::int64_t end = offset;
      for (;;) {
        const int r = av_read_frame(in.f, pkt.p);
        if (r == AVERROR_EOF) break;
        check_av(r, parts[i], "cannot read a frame");
        if (pkt.p->pts != AV_NOPTS_VALUE) {
          pkt.p->pts += offset;
          end = std::max(end, pkt.p->pts + pkt.p->duration);
        }
        if (pkt.p->dts != AV_NOPTS_VALUE) {
          pkt.p->dts += offset - (max_lead - lead[i]);
          if (last_dts != AV_NOPTS_VALUE && pkt.p->dts <= last_dts)
            throw UserError("movie '" + parts[i].string() +
                            "': its frames would overlap those of the part before");
          last_dts = pkt.p->dts;
        }
        pkt.p->stream_index = 0;
        pkt.p->pos = -1;
        av_packet_rescale_ts(pkt.p, s->time_base, st->time_base);
        check_av(av_write_frame(o.f, pkt.p), out, "cannot write a frame");
        av_packet_unref(pkt.p);
      }
      offset = end;
    }
    check_av(av_write_trailer(o.f), out, "cannot write the trailer");
    check_av(avio_closep(&o.f->pb), out, "cannot close the file");
    std::error_code ec;
    fs::rename(tmp, out, ec);
    if (ec)
      throw UserError("movie '" + out.string() +
                      "': cannot move the finished file into place: " + ec.message());
  } catch (...) {
    remove_tmp();
    throw;
  }
}

fs::path MovieParts::folder(const fs::path& movie) {
  return fs::path(movie).replace_extension(".parts");
}

MovieParts::MovieParts(const fs::path& movie, const MovieOptions& options, int parts_done,
                       std::int64_t frames_done)
    : movie_(movie),
      dir_(folder(movie)),
      options_(options),
      parts_(parts_done),
      parts_done_(parts_done),
      frames_(frames_done) {
  GS_CHECK(parts_done >= 0 && frames_done >= 0);
  if (!on_disk(movie, parts_done))
    throw UserError("'" + dir_.string() + "' lacks some of its " + std::to_string(parts_done) +
                    " parts: the movie cannot go on from its checkpoint");
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw UserError("cannot create '" + dir_.string() + "': " + ec.message());
  // A kill leaves parts after the checkpoint's and the temporary file of the open one.
  std::vector<fs::path> doomed;
  for (const auto& entry : fs::directory_iterator(dir_, ec)) {
    bool kept = false;
    for (int k = 0; k < parts_done && !kept; ++k) kept = entry.path() == part_path(k);
    if (!kept) doomed.push_back(entry.path());
  }
  for (const auto& p : doomed) fs::remove(p, ec);
  open_part();
}

MovieParts::~MovieParts() {
  open_.reset();  // a part being written when an exception unwinds removes its partial file
  if (keep_) return;
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

fs::path MovieParts::part_path(const fs::path& dir, int k) {
  char name[32];
  std::snprintf(name, sizeof name, "part_%04d.mp4", k);
  return dir / name;
}

bool MovieParts::on_disk(const fs::path& movie, int parts) {
  for (int k = 0; k < parts; ++k)
    if (!fs::is_regular_file(part_path(folder(movie), k))) return false;
  return true;
}

void MovieParts::open_part() {
  open_ = std::make_unique<MovieWriter>(part_path(parts_), options_);
  encoder_name_ = open_->encoder_name();
  width_ = open_->encoded_width();
  height_ = open_->encoded_height();
}

void MovieParts::add(Image frame) {
  if (open_ && open_->frames_added() > 0 && at_part_end()) cut();
  if (!open_) open_part();
  open_->add(std::move(frame));
  ++frames_;
}

void MovieParts::cut() {
  if (!open_) return;
  if (open_->frames_added() == 0) {
    open_->discard();
  } else {
    open_->finish();
    sync_file(part_path(parts_));
    ++parts_;
  }
  open_.reset();
}

void MovieParts::discard() {
  if (open_) open_->discard();
  open_.reset();
  keep_ = false;
  parts_ = 0;
  frames_ = 0;
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

bool MovieParts::finish(bool keep_parts) {
  cut();
  if (parts_ == 0) return false;
  if (parts_ == 1 && !keep_parts) {
    std::error_code ec;
    fs::rename(part_path(0), movie_, ec);
    if (ec)
      throw UserError("movie '" + movie_.string() +
                      "': cannot move the finished file into place: " + ec.message());
  } else {
    std::vector<fs::path> parts;
    for (int k = 0; k < parts_; ++k) parts.push_back(part_path(k));
    try {
      join_movies(parts, movie_);
    } catch (...) {
      // Parts made before this process (a resumed movie) are not made again by it: a refused
      // join leaves them for a look, with the checkpoint that names them.
      if (parts_done_ > 0) keep_ = true;
      throw;
    }
  }
  if (keep_parts) keep_ = true;
  return true;
}

}  // namespace gs::render
