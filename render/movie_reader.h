#pragma once
// Decodes a movie frame by frame through FFmpeg's libraries, for `grainshock compare` and the
// movie tests. The header needs no FFmpeg include: the stream's properties are plain numbers
// (libavcodec's enum values where FFmpeg has an enum).
#include <cstdint>
#include <filesystem>
#include <memory>

#include "render/image.h"

namespace gs::render {

struct MovieInfo {
  int codec_id = 0;  // AVCodecID
  int width = 0, height = 0;
  int avg_rate_num = 0, avg_rate_den = 1;  // average frame rate
  int r_rate_num = 0, r_rate_den = 1;      // the stream's base frame rate
  double duration = -1;                    // seconds, as a player shows it; -1 unknown
  std::int64_t nb_frames = 0;              // as the container says
  int color_range = 0, color_space = 0, color_primaries = 0, color_trc = 0;  // AVColor*
};

class MovieReader {
 public:
  // Opens the file and its best video stream. UserError naming the path when it is missing or
  // holds no video stream that libavcodec decodes.
  explicit MovieReader(const std::filesystem::path& path);
  ~MovieReader();
  MovieReader(const MovieReader&) = delete;
  MovieReader& operator=(const MovieReader&) = delete;

  const MovieInfo& info() const { return info_; }

  // Decodes the next frame in presentation order; false after the last. UserError on a decoding
  // error, naming the path and the frame.
  bool next();
  int frames_read() const { return frames_; }

  // The current frame back to RGBA with BT.709 limited-range coefficients (what MovieWriter
  // encodes with), at the decoded size.
  Image rgb() const;
  // Y of the current frame at (x, y), as stored (limited range: 16 black .. 235 white).
  int luma(int x, int y) const;

  struct Av;  // the libav state, private to movie_reader.cpp

 private:
  std::filesystem::path path_;
  std::unique_ptr<Av> av_;
  MovieInfo info_;
  int frames_ = 0;
  bool flushed_ = false;
};

}  // namespace gs::render
