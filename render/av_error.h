#pragma once
// libav error codes as one line for the user; private to the FFmpeg-based sources of render/.
#include <cstdio>
#include <filesystem>
#include <string>

extern "C" {
#include <libavutil/error.h>
}

#include "sim/error.h"

namespace gs::render {

inline std::string av_error_text(int err) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  if (av_strerror(err, buf, sizeof buf) < 0) std::snprintf(buf, sizeof buf, "libav error %d", err);
  return buf;
}

// Library calls that fail for reasons outside the program (disk full, unwritable folder, an
// encoder refusing a size, a file that is no movie) are the user's to fix: one line naming the
// movie and libav's reason.
inline void check_av(int ret, const std::filesystem::path& path, const char* what) {
  if (ret < 0)
    throw UserError("movie '" + path.string() + "': " + what + ": " + av_error_text(ret));
}

}  // namespace gs::render
