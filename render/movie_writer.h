#pragma once
// Streams RGBA images into a movie file through FFmpeg's libraries (libavformat, libavcodec,
// libswscale). A worker thread converts, encodes and muxes while the caller renders the next
// frame; add() blocks only when the bounded queue is full.
//
// The file only ever appears under its final name complete: it is written to a hidden temporary
// file in the same folder and renamed after the trailer is written. An error (or destruction during
// stack unwinding) removes the temporary file instead.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "render/image.h"

namespace gs::render {

struct MovieOptions {
  // "h264" (libx264, falling back to "mpeg4" when libavcodec has no libx264), "libx264" (no
  // fallback) or "mpeg4" (MPEG-4 Part 2, the encoder built into every libavcodec).
  std::string codec = "h264";
  double fps = 30;
  // H.264 constant rate factor, 0 (lossless) .. 51; 18 is visually lossless for our frames.
  // mpeg4 has no CRF: it uses the fixed quantiser qscale = crf / 6 (18 -> 3, a high quality).
  int crf = 18;
  // libx264 speed/size trade-off. On the Fig. 1 job's frames at CRF 18, ultrafast
  // encodes a 1080p frame in 6 ms of CPU where veryfast took 17, with a higher PSNR against the
  // pictures (57 dB against 47), for a file 2.5 times as large (7.5 MB for the 8 s movie).
  std::string preset = "ultrafast";
  // Size of the frames given to add(). Odd sizes are padded to even ones, see MovieWriter.
  int width = 0;
  int height = 0;
  // Frames of each part of a movie made in parts (MovieParts): a part starts with a key frame
  // and is encoded alone, so that the movie's bytes are the same wherever it was stopped and
  // resumed; a killed movie goes on from the last whole part.
  int keyint = 120;
  int queue_frames = 4;  // frames waiting for the encoder before add() blocks
  int threads = 0;       // encoder threads, 0 = libavcodec chooses
};

// Throws UserError naming the option if `o` cannot make a movie (size, fps, crf, codec name), so
// that a command can refuse bad flags before it creates anything. The constructor calls it too.
void check_movie_options(const MovieOptions& o);

class MovieWriter {
 public:
  // Opens the encoder and the output at once, so a bad path or codec is reported before any
  // simulation runs. The container follows the extension of `path` (.mp4, .mkv, ...).
  // Throws UserError naming the input on an unknown codec, bad options or an unwritable path.
  MovieWriter(const std::filesystem::path& path, const MovieOptions& options);
  // Finishes the movie, unless the destructor runs because an exception is unwinding the stack:
  // then the partial file is removed.
  ~MovieWriter();
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  // Queues one frame of options.width x options.height (checked). Blocks while the queue is full.
  // Rethrows an error of the worker thread (the partial file is then already removed).
  void add(Image frame);

  // A frame the encoder is done with, or an empty image: its memory for the next picture
  // (Renderer::recycle), since an 8 MB 1080p picture on fresh pages costs 2000 page faults.
  Image spare();

  // Flushes the encoder, writes the trailer and moves the file to its final name. Idempotent.
  void finish();

  // Stops without a movie: the worker is stopped and the partial file removed. Idempotent.
  void discard();

  const std::filesystem::path& path() const { return path_; }
  // The encoder actually used ("libx264" or "mpeg4"), after the h264 -> mpeg4 fallback.
  const std::string& encoder_name() const { return encoder_name_; }
  // Size of the encoded pictures: the frame size rounded up to even numbers.
  int encoded_width() const { return encoded_width_; }
  int encoded_height() const { return encoded_height_; }
  std::int64_t frames_added() const { return frames_added_; }

  struct Av;  // the libav state, private to movie_writer.cpp

 private:
  void worker_loop();
  void encode_frame(const Image& frame);
  void stop_worker();
  void remove_partial() noexcept;

  std::filesystem::path path_;
  std::filesystem::path temp_path_;
  MovieOptions options_;
  std::string encoder_name_;
  int encoded_width_ = 0;
  int encoded_height_ = 0;
  std::int64_t frames_added_ = 0;
  int uncaught_at_construction_ = 0;
  bool done_ = false;

  std::unique_ptr<Av> av_;

  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Image> queue_;
  Image spare_;  // the last frame encoded
  bool closing_ = false;    // no more frames: the worker drains, flushes and writes the trailer
  bool cancelled_ = false;  // stop at once, drop the queue
  bool worker_done_ = false;
  std::exception_ptr worker_error_;
  std::thread worker_;
};

}  // namespace gs::render
