#pragma once
// Two error channels, as in pbrt-v4:
//  - UserError: the input is wrong (a flag, a file, a density). The message names the input and
//    is printed as one line by the command line; the program exits non-zero.
//  - GS_CHECK: an invariant of the code is broken. That is a bug, never the user's fault; the
//    process aborts with file and line so that it cannot go on producing wrong physics.
#include <stdexcept>
#include <string>

namespace gs {

class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] void check_failed(const char* expr, const char* file, int line,
                               const std::string& msg);

}  // namespace gs

#define GS_CHECK(cond)                                              \
  do {                                                              \
    if (!(cond)) [[unlikely]]                                       \
      ::gs::check_failed(#cond, __FILE__, __LINE__, std::string()); \
  } while (0)

#define GS_CHECK_MSG(cond, msg)                             \
  do {                                                      \
    if (!(cond)) [[unlikely]]                               \
      ::gs::check_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
