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

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ < 0) return;
  ::close(fd_);
  std::error_code ec;
  std::filesystem::remove(tmp_, ec);
}

void AtomicFileWriter::fail(const std::string& why) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::error_code ec;
  std::filesystem::remove(tmp_, ec);
  throw UserError("cannot write '" + path_.string() + "': " + why);
}

void AtomicFileWriter::open(const std::filesystem::path& path) {
  GS_CHECK(fd_ < 0);
  path_ = path;
  tmp_ = path;
  tmp_ += ".tmp." + std::to_string(::getpid());
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail(std::strerror(errno));
}

void AtomicFileWriter::write(std::string_view piece) {
  GS_CHECK(fd_ >= 0);
  const char* p = piece.data();
  std::size_t left = piece.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(std::strerror(errno));
    p += n, left -= static_cast<std::size_t>(n);
  }
}

void AtomicFileWriter::finish(std::string_view head) {
  GS_CHECK(fd_ >= 0);
  for (std::size_t done = 0; done < head.size();) {
    const ssize_t n = ::pwrite(fd_, head.data() + done, head.size() - done,
                               static_cast<off_t>(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(std::strerror(errno));
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd_) != 0) {
    fd_ = -1;
    fail(std::strerror(errno));
  }
  fd_ = -1;
  std::error_code ec;
  std::filesystem::rename(tmp_, path_, ec);
  if (ec) {
    std::filesystem::remove(tmp_, ec);
    throw UserError("cannot write '" + path_.string() + "': " + ec.message());
  }
}

}  // namespace gs
