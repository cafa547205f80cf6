#pragma once
// The output folder of a command: never overwrites earlier results by accident, is written by
// one process at a time, and is cleaned of what killed writers left in it.
#include <filesystem>
#include <span>
#include <string>

namespace gs {

// Creates `dir` for a new run. An existing non-empty folder is refused unless `force`. With it,
// the names in `replaced` (the files and folders the command writes) are removed first, so
// that the folder never mixes two runs, even if the new one is killed early; anything else in
// the folder is left alone. The folder is locked (lock_output_dir) before anything in it is
// removed or written, and refused if another process wrote into it between the check and the
// lock.
std::filesystem::path prepare_output_dir(const std::string& dir, bool force,
                                         std::span<const char* const> replaced = {});

// Holds an exclusive lock on `dir` until the process ends (flock on the folder itself, so that
// nothing is added to it): a second run or resume into the same folder is refused.
void lock_output_dir(const std::filesystem::path& dir);

// Removes what killed writers left in `dir` and its snapshots/ and frames/: temporaries of
// atomic writes (NAME.tmp.PID, io/atomic_file.h) and of movies (.NAME.PID.partial).
void remove_leftovers(const std::filesystem::path& dir);

}  // namespace gs
