#pragma once
// A movie of the spreading front: runs one realisation and streams its frames into a movie file,
// with no intermediate files, or draws stored snapshot files in order of their time. Used by
// `grainshock movie` and `grainshock run --movie`; both kinds share one frame loop.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/snapshot_file.h"
#include "jobs/progress.h"
#include "render/movie_writer.h"
#include "sim/config.h"
#include "sim/messages.h"

namespace gs::jobs {

// The flags of `grainshock movie` beyond the physics, with its defaults.
struct FrontMovieOptions {
  int frames = 240;
  std::string spacing = "log";  // lin: t-max / frames apart; log: from t_start to t-max
  double t_start = 1;
  // The stills' size. At 1280x720 the Fig. 1 job's late band has discs of about 1.4 px radius,
  // mostly antialiased rim, whose blend with the background reads as lighter colours: the edge
  // contrast (render/contrast.h) of its last frames fell to +0.10 (+0.15 at 1920x1080, as in
  // the stills).
  render::MovieOptions movie{.width = 1920, .height = 1080};
  std::string camera = "follow";  // follow: the front, smoothly; fixed: the whole periodic box
  // auto: scaled-speed for a kick (one colour is one v / v_rms in every frame), else speed.
  std::string colour_by = "auto", scale = "auto", colormap = "magma", background = "light";
  // MIN MAX; empty: the scaled fields' fixed range, else spans every frame's 1-99 percentiles.
  std::vector<double> range;
  bool range_per_frame = false;  // each frame its own 1-99 percentiles
  bool inset = false;            // the profile across the band, bottom left
  bool show_inactive = false;
  // 3D: unset, a kick's movie is cut to a slab (render::kKickSlab: the whole shell would show
  // only its skin) and others' files are drawn whole, as `render` draws them.
  std::optional<double> slab;
  bool clip = false;  // 3D: cut away the half nearer than the plane through the front's centre
  double azimuth = 30, elevation = 20;
  double orbit = 0;          // 3D: total azimuth turned over the movie, degrees
  bool keep_frames = false;  // also write DIR/frames/frame_NNNNN.png
  std::string backend = "auto";
  bool quiet = false;
  ProgressFactory progress;  // the line of each pass; none by default
  MessageSink messages;      // notes: frames written, what a reader assumed; none by default
  ReadOptions read;          // stored snapshots: --dt, --unwrap (--dim is the simulation's flag)
};

// Throws UserError naming the flag if these options cannot make a movie of this run. Touches
// nothing on disk, so a command can call it before it makes its output folder.
void check_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o);

struct FrontMovieResult {
  std::int64_t frames = 0;  // in the movie
  bool stopped = false;     // by SIGINT/SIGTERM (sim/stop.h); the movie is complete all the same
};

// How a live movie keeps checkpoints (`grainshock movie`; `run --movie`, whose run is
// checkpointed, makes its movie again after a resume instead).
struct MovieCheckpoints {
  std::string spec;    // the text of movie.toml: a resume refuses the checkpoint of another movie
  double every = 300;  // wall seconds between checkpoints; 0: at the start and on a stop only
};

std::filesystem::path movie_checkpoint_path(const std::filesystem::path& dir);
std::filesystem::path previous_movie_checkpoint_path(const std::filesystem::path& dir);

// Writes dir/movie.mp4 (dir must exist). A stop request ends it early with a playable movie of
// the frames so far, or no file if there were none. With `checkpoints`, the movie is written in
// parts (render/movie_parts.h), cut at each checkpoint; a stopped movie keeps its parts and
// checkpoint for resume_front_movie, and a finished one removes them.
FrontMovieResult write_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o,
                                   const std::filesystem::path& dir,
                                   const MovieCheckpoints* checkpoints = nullptr);
// Goes on from dir's checkpoint and ends with the movie of the frames an uninterrupted
// write_front_movie draws (the same PNGs with --keep-frames; the movie's parts are joined
// without encoding again). A movie killed after it was joined is finished: its leftover
// checkpoints and parts are removed (and the result has no frames). UserError, with nothing
// touched, for a finished movie, a folder without a checkpoint, one refused by io/checkpoint.h
// and one of another movie.toml.
FrontMovieResult resume_front_movie(const PhysicsConfig& physics, const FrontMovieOptions& o,
                                    const std::filesystem::path& dir,
                                    const MovieCheckpoints& checkpoints);

class RunLoop;

// Whether write_run_movie can draw this movie: in one pass, as the run goes, which needs the
// colour range known ahead (a kick's scaled speed has a fixed one; plain speed without --range
// spans every frame, found by a pass ahead).
bool movie_in_one_pass(const PhysicsConfig& physics, const FrontMovieOptions& o);
// The movie write_front_movie(physics, o, dir) makes, frame for frame, drawn as `loop` (a new
// run of `physics`, not yet started) runs to the last frame's time, t-max, which replays nothing.
// A stop ends it as the loop's run does (the loop's checkpoint written), with a playable movie
// of the frames so far.
FrontMovieResult write_run_movie(RunLoop& loop, const PhysicsConfig& physics,
                                 const FrontMovieOptions& o, const std::filesystem::path& dir);

// A movie of stored snapshots, prepared so that bad input (a file that cannot be opened, flags
// that do not fit the first frame) is refused before an output folder is made.
class StoredMovie {
 public:
  struct Impl;
  explicit StoredMovie(std::unique_ptr<Impl> impl);
  ~StoredMovie();
  StoredMovie(StoredMovie&&) noexcept;
  std::size_t frames() const;

 private:
  friend FrontMovieResult write_stored_movie(StoredMovie& m, const std::filesystem::path& dir);
  std::unique_ptr<Impl> impl_;
};

// Opens every file (a file of several frames gives several movie frames) and reads the first
// frame: UserError naming the file for one that cannot be opened or holds no frame, and for a
// --color-by field the first frame lacks (listing those it has) or --orbit on 2D frames. Reads
// every frame now only when the colour range must span them all (that pass also orders them).
StoredMovie prepare_stored_movie(const std::vector<std::string>& files, const FrontMovieOptions& o);
// Writes dir/movie.mp4 (dir must exist), each frame read one ahead on a second thread. A frame
// that cannot be read, has no velocities when coloured by a speed, lacks the field, or differs
// from the first in dimension or box ends it with a UserError naming the file (and the frame, in
// a file of several); what it wrote (the partial movie, --keep-frames PNGs and their folder) is
// removed again.
FrontMovieResult write_stored_movie(StoredMovie& m, const std::filesystem::path& dir);

}  // namespace gs::jobs
