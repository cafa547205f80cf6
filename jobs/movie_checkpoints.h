#pragma once
// A live movie's checkpoints (io/checkpoint.h), for `grainshock resume` of a movie folder: the
// pass and the frame reached, the colour ranges pass 1 has found, the following camera, the parts
// of the movie on disk (render/movie_parts.h) and the engine.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jobs/frame_loop.h"
#include "jobs/movie.h"
#include "jobs/movie_plan.h"
#include "jobs/progress.h"
#include "render/follow_camera.h"
#include "render/movie_parts.h"
#include "sim/engine.h"
#include "sim/state_stream.h"

namespace gs::jobs {

enum Pass : std::uint32_t { kRangePass = 1, kMoviePass = 2 };

void remove_movie_checkpoints(const std::filesystem::path& dir);

// A live movie's checkpoints (io/checkpoint.h): the pass and the frame reached, the colour
// ranges pass 1 has found, the following camera, the parts of the movie on disk and the engine.
// Each is written whole, the previous one kept until it is in place.
class LiveCheckpoints {
 public:
  LiveCheckpoints(const std::filesystem::path& dir, const MovieCheckpoints& c,
                  const PhysicsConfig& physics)
      : dir_(dir),
        spec_(c.spec),
        every_(c.every),
        id_{physics.dim, static_cast<std::uint64_t>(physics.particles)} {}
  // The first is due at once, so that a kill at any moment leaves one; then every `every` s.
  bool due() const { return !any_ || (every_ > 0 && seconds_since(last_) >= every_); }
  // After a checkpoint is written or read; `part_sums`: the checksums of the parts it names.
  void resumed(std::vector<std::uint64_t> part_sums) {
    part_sums_ = std::move(part_sums);
    resumed();
  }
  void resumed() {
    any_ = true;
    last_ = std::chrono::steady_clock::now();
  }
  void write(Pass pass, std::size_t next, std::size_t frames, const std::vector<FrameScan>& scans,
             const std::optional<render::FollowCamera>& follow, const render::MovieParts& movie,
             const Simulation& sim);

 private:
  std::filesystem::path dir_;
  std::string spec_;
  double every_;
  StateIdentity id_;
  bool any_ = false;
  std::chrono::steady_clock::time_point last_;
  std::vector<std::uint64_t> part_sums_;  // of the whole parts on disk, taken once each
};

// What a live movie goes on from.
struct Resumed {
  Pass pass = kRangePass;
  std::size_t next = 0;
  std::vector<FrameScan> scans;
  std::optional<render::FollowCamera> follow;
  int parts = 0;
  std::int64_t part_frames = 0;
  std::vector<std::uint64_t> part_sums;  // io/checkpoint.h file_checksum of each part
  std::unique_ptr<Simulation> sim;
};

// Reads dir's checkpoint, refusing (UserError, one line; nothing touched) a folder without one,
// one that CheckpointReader refuses, and one of another movie.toml. `camera` is the following
// camera as this movie makes it, to be loaded with the state.
Resumed read_live_checkpoint(const std::filesystem::path& dir, const MovieCheckpoints& c,
                             const PhysicsConfig& physics, const MoviePlan& plan,
                             std::size_t frames, const render::FollowCamera& camera);

// UserError naming the first part of `movie` whose bytes are not those checksummed when it was
// written (a damaged disk, a hand edit): joined, it would spoil the movie. Nothing is touched.
void check_parts(const std::filesystem::path& movie, const std::vector<std::uint64_t>& sums);

// A finished movie joins its parts into movie.mp4, then removes its checkpoints, then its parts:
// a kill after the join leaves a finished movie whose leftovers only need removing.
FrontMovieResult remove_leftovers_of_finished(const std::filesystem::path& dir, bool quiet,
                                              const MessageSink& messages);

}  // namespace gs::jobs
