#include "jobs/movie_checkpoints.h"

#include <cstdio>

#include "io/checkpoint.h"
#include "sim/error.h"

namespace gs::jobs {

void remove_movie_checkpoints(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::remove(movie_checkpoint_path(dir), ec);
  std::filesystem::remove(previous_movie_checkpoint_path(dir), ec);
}

void LiveCheckpoints::write(Pass pass, std::size_t next, std::size_t frames,
                            const std::vector<FrameScan>& scans,
                            const std::optional<render::FollowCamera>& follow,
                            const render::MovieParts& movie, const Simulation& sim) {
  CheckpointWriter out(movie_checkpoint_path(dir_), previous_movie_checkpoint_path(dir_), id_);
  out.string(spec_);
  out.value(static_cast<std::uint32_t>(pass));
  out.value(static_cast<std::uint64_t>(next));
  out.value(static_cast<std::uint64_t>(frames));
  out.value(static_cast<std::uint64_t>(scans.size()));
  for (const FrameScan& f : scans) {  // all that fixed_range() reads of them
    out.value(static_cast<std::uint8_t>(f.any_active));
    out.value(f.range.first);
    out.value(f.range.second);
  }
  out.value(static_cast<std::uint8_t>(follow.has_value()));
  if (follow) follow->save(out);
  out.value(static_cast<std::int32_t>(movie.parts()));
  out.value(static_cast<std::int64_t>(movie.frames_added()));
  // Each part's checksum, taken once, just after it was synced: a resume checks the parts
  // before it joins them.
  for (int k = static_cast<int>(part_sums_.size()); k < movie.parts(); ++k)
    part_sums_.push_back(file_checksum(movie.part(k)));
  part_sums_.resize(static_cast<std::size_t>(movie.parts()));
  for (std::uint64_t sum : part_sums_) out.value(sum);
  sim.save(out);
  out.commit();
  resumed();
}

Resumed read_live_checkpoint(const std::filesystem::path& dir, const MovieCheckpoints& c,
                             const PhysicsConfig& physics, const MoviePlan& plan,
                             std::size_t frames, const render::FollowCamera& camera) {
  const std::filesystem::path file = checkpoint_to_resume(
      movie_checkpoint_path(dir), previous_movie_checkpoint_path(dir), "movie checkpoint");
  CheckpointReader in(file);
  if (in.string() != c.spec)
    throw UserError("the checkpoint '" + file.string() + "' is of another movie than '" +
                    (dir / "movie.toml").string() + "' describes");
  Resumed r;
  const auto pass = in.value<std::uint32_t>();
  in.expect(pass == kRangePass || pass == kMoviePass);
  r.pass = static_cast<Pass>(pass);
  r.next = in.value<std::uint64_t>();
  in.expect(in.value<std::uint64_t>() == frames && r.next <= frames);
  const auto scans = in.value<std::uint64_t>();
  in.expect(scans == (r.pass == kRangePass ? r.next : plan.need_range ? frames : 0));
  r.scans.resize(scans);
  for (FrameScan& f : r.scans) {
    f.any_active = in.value<std::uint8_t>() != 0;
    in.value(f.range.first);
    in.value(f.range.second);
  }
  if (in.value<std::uint8_t>()) {
    r.follow.emplace(camera);
    r.follow->load(in);
  }
  r.parts = in.value<std::int32_t>();
  r.part_frames = in.value<std::int64_t>();
  // Every frame before the next one is in a whole part.
  in.expect(r.parts >= 0 && r.part_frames >= r.parts &&
            r.part_frames == (r.pass == kMoviePass ? std::int64_t(r.next) : 0));
  r.part_sums.resize(static_cast<std::size_t>(r.parts));
  for (std::uint64_t& sum : r.part_sums) in.value(sum);
  r.sim = load_simulation(physics, in);
  in.finish();
  return r;
}

void check_parts(const std::filesystem::path& movie, const std::vector<std::uint64_t>& sums) {
  const auto dir = render::MovieParts::folder(movie);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    const auto part = render::MovieParts::part_path(dir, static_cast<int>(k));
    if (file_checksum(part) != sums[k])
      throw UserError("movie part '" + part.string() +
                      "' is damaged (not the bytes it was written with); the parts are left as "
                      "they are; make the movie again with: grainshock movie --config " +
                      (movie.parent_path() / "movie.toml").string() + " --out " +
                      movie.parent_path().string() + " --force");
  }
}

FrontMovieResult remove_leftovers_of_finished(const std::filesystem::path& dir, bool quiet,
                                              const MessageSink& messages) {
  remove_movie_checkpoints(dir);
  std::error_code ec;
  std::filesystem::remove_all(render::MovieParts::folder(dir / "movie.mp4"), ec);
  if (!quiet)
    tell(messages, MessageKind::Note,
         dir.string() + " had finished; its leftover checkpoints and parts are removed");
  return {0, false};
}

}  // namespace gs::jobs
