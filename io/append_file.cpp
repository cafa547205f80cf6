#include "io/append_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "sim/error.h"

namespace gs {

AppendFile::AppendFile(const std::filesystem::path& path, std::uint64_t keep) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (keep == 0 ? O_TRUNC : 0), 0644);
  if (fd_ < 0) throw UserError("cannot write '" + path.string() + "': " + std::strerror(errno));
  struct stat st {};
  const bool ok = ::fstat(fd_, &st) == 0;
  if (!ok || static_cast<std::uint64_t>(st.st_size) < keep) {
    ::close(fd_);
    throw UserError("'" + path.string() + "' is shorter (" + std::to_string(st.st_size) +
                    " bytes) than the " + std::to_string(keep) + " bytes it had");
  }
  if (keep > 0 && (::ftruncate(fd_, static_cast<off_t>(keep)) != 0 ||
                   ::lseek(fd_, static_cast<off_t>(keep), SEEK_SET) < 0)) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw UserError("cannot write '" + path.string() + "': " + why);
  }
  size_ = keep;
}

AppendFile::~AppendFile() {
  if (fd_ >= 0) ::close(fd_);
}

void AppendFile::append(std::string_view record) {
  const char* p = record.data();
  std::size_t left = record.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string why = std::strerror(errno);
      if (::ftruncate(fd_, static_cast<off_t>(size_)) == 0)  // the part that fitted goes again
        ::lseek(fd_, static_cast<off_t>(size_), SEEK_SET);
      throw UserError("cannot write '" + path_.string() + "': " + why);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  size_ += record.size();
}

}  // namespace gs
