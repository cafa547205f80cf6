#pragma once
// A movie made in parts, so that a long movie can go on from a checkpoint after a kill: the
// frames go to DIR/movie.parts/part_NNNN.mp4, each part a whole movie of its own (MovieWriter)
// of MovieOptions::keyint frames (counted from the movie's first frame; a stop may cut one
// short), and finish() joins them into the movie without encoding again (join_movies). Each
// part being encoded alone, a movie is the same bytes whether or not it was stopped and resumed
// at a part's end, and a checkpoint is taken only there. A movie of one part is only renamed.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "render/movie_writer.h"

namespace gs::render {

// Copies the packets of `parts` (movies of one video stream each, made by MovieWriter with the
// same options) one after another into `out`, each part's times shifted by the length of those
// before it. Every part begins with a key frame, so `out` decodes frame for frame as the parts
// do. `out` appears complete or not at all. UserError naming a part that cannot be read or
// does not match the first (codec, size, time base, stream headers).
void join_movies(const std::vector<std::filesystem::path>& parts, const std::filesystem::path& out);

class MovieParts {
 public:
  // The folder of a movie's parts: beside it, named after it (movie.mp4 -> movie.parts).
  static std::filesystem::path folder(const std::filesystem::path& movie);
  // Whether the first `parts` parts of `movie` are on disk.
  static bool on_disk(const std::filesystem::path& movie, int parts);

  // Goes on after the first `parts_done` parts in folder(movie), which hold `frames_done` frames;
  // what a killed writer left after them is removed. The first part is opened at once, so that
  // an unwritable folder or a bad option is reported before any work.
  MovieParts(const std::filesystem::path& movie, const MovieOptions& options, int parts_done = 0,
             std::int64_t frames_done = 0);
  // Removes the parts unless finish(false) has put the movie in place or keep() was called, or
  // the join of a movie that went on from parts on disk failed.
  ~MovieParts();
  MovieParts(const MovieParts&) = delete;
  MovieParts& operator=(const MovieParts&) = delete;

  // Cuts the open part first when it is whole (keyint frames since the movie's first frame).
  void add(Image frame);
  // Whether the frames added so far end at a part's end (where a checkpoint may be taken).
  bool at_part_end() const { return frames_ % options_.keyint == 0; }
  // Part k's file, in this movie's folder of parts or in `dir`.
  std::filesystem::path part(int k) const { return part_path(dir_, k); }
  static std::filesystem::path part_path(const std::filesystem::path& dir, int k);
  // A frame the open part's encoder is done with, or an empty image (MovieWriter::spare).
  Image spare() { return open_ ? open_->spare() : Image{}; }
  // Finishes the open part, if a frame went into it, and syncs it to disk: after cut(), parts()
  // parts holding frames_added() frames are whole on disk.
  void cut();
  // cut(), then the movie: the parts joined (or the one part renamed). With `keep_parts` the
  // parts stay for a run to go on from them (a joined movie of the frames so far). Without any
  // frame, no movie is written. Returns whether one was.
  bool finish(bool keep_parts = false);
  // Leaves the parts on disk when this object goes (a stopped movie that will be resumed).
  void keep() { keep_ = true; }
  // No movie: the open part and every part on disk are removed.
  void discard();

  int parts() const { return parts_; }
  std::int64_t frames_added() const { return frames_; }
  const std::filesystem::path& path() const { return movie_; }
  const std::string& encoder_name() const { return encoder_name_; }
  int encoded_width() const { return width_; }
  int encoded_height() const { return height_; }

 private:
  std::filesystem::path part_path(int k) const { return part_path(dir_, k); }
  void open_part();

  std::filesystem::path movie_, dir_;
  MovieOptions options_;
  std::unique_ptr<MovieWriter> open_;  // the part frames go to; null after cut()
  int parts_ = 0;                      // whole parts on disk
  int parts_done_ = 0;                 // of them, those made before this object
  std::int64_t frames_ = 0;            // in whole parts and the open one
  std::string encoder_name_;
  int width_ = 0, height_ = 0;
  bool keep_ = false;
};

}  // namespace gs::render
