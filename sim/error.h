#pragma once
// Two error channels, as in pbrt-v4:
//  - UserError: the input is wrong (a flag, a file, a density). The message names the input and
//    is printed as one line by the command line; the program exits non-zero (UsageError: 2).
//  - GS_CHECK: an invariant of the code is broken. That is a bug, never the user's fault; the
//    process aborts with file and line so that it cannot go on producing wrong physics.
#include <stdexcept>
#include <string>

namespace gs {

class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A UserError about the command line itself: a flag's value outside what the flag accepts (its
// range, its words), or flags that exclude each other. The command line exits 2 for it, as for
// the malformed values CLI11 refuses, and 1 for every other UserError (a file, a folder, physics
// that cannot fit), so one value gives one exit code whichever subcommand checks it.
class UsageError : public UserError {
 public:
  using UserError::UserError;
};

[[noreturn]] void check_failed(const char* expr, const char* file, int line,
                               const std::string& msg);

}  // namespace gs

#define GS_CHECK(cond)                                              \
  do {                                                              \
    if (!(cond)) [[unlikely]]                                       \
      ::gs::check_failed(#cond, __FILE__, __LINE__, std::string()); \
  } while (0)

// GS_DCHECK: a GS_CHECK for hot loops (once per neighbour, per event), compiled only into builds
// without NDEBUG (Debug); Release (and RelWithDebInfo) keeps GS_CHECK wherever a broken
// invariant would make a run's results wrong, and uses this where a cheaper check outside the
// loop, or the geometry itself, already guards the same invariant.
#ifdef NDEBUG
#define GS_DCHECK(cond) \
  do {                  \
  } while (false && (cond))
#else
#define GS_DCHECK(cond) GS_CHECK(cond)
#endif

#define GS_CHECK_MSG(cond, msg)                             \
  do {                                                      \
    if (!(cond)) [[unlikely]]                               \
      ::gs::check_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
