#include "sim/error.h"

#include <cstdio>
#include <cstdlib>

namespace gs {

void check_failed(const char* expr, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr, "grainshock: internal error: CHECK(%s) failed at %s:%d%s%s\n", expr, file,
               line, msg.empty() ? "" : ": ", msg.c_str());
  std::abort();
}

}  // namespace gs
