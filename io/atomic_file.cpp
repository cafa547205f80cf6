#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "sim/error.h"

namespace gs {

void write_file_atomic(const std::filesystem::path& path, std::string_view text) {
  write_file_atomic(path, {text});
}

void write_file_atomic(const std::filesystem::path& path,
                       std::initializer_list<std::string_view> pieces) {
  namespace fs = std::filesystem;
  // The pid keeps two processes writing the same file from sharing a temporary.
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid());
  std::error_code ec;
  {
    // POSIX calls rather than a stream, for the OS reason of a failure (a full disk).
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    bool ok = fd >= 0;
    for (const std::string_view text : pieces) {
      const char* p = text.data();
      std::size_t left = text.size();
      while (ok && left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        ok = n > 0;
        if (ok) p += n, left -= static_cast<std::size_t>(n);
      }
    }
    const std::string why = std::strerror(errno);
    if (fd >= 0 && ::close(fd) != 0) ok = false;
    if (!ok) {
      fs::remove(tmp, ec);
      throw UserError("cannot write '" + path.string() + "': " + why);
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path.string() + "': " + why);
  }
}

}  // namespace gs
