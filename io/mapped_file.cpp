#include "io/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "sim/error.h"

namespace gs {

struct MappedFile::Mapping {
  void* address = nullptr;
  std::size_t length = 0;
  std::string owned;  // from_bytes
  ~Mapping() {
    if (address) ::munmap(address, length);
  }
};

std::string not_a_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  switch (fs::status(path, ec).type()) {
    case fs::file_type::regular: return {};
    case fs::file_type::not_found: return "no such file";
    case fs::file_type::directory: return "is a directory";
    case fs::file_type::fifo: return "is a pipe (not a regular file)";
    case fs::file_type::socket: return "is a socket (not a regular file)";
    case fs::file_type::block:
    case fs::file_type::character: return "is a device (not a regular file)";
    default: return ec ? ec.message() : "is not a regular file";
  }
}

MappedFile MappedFile::open(const std::string& path) {
  // O_NONBLOCK: opening a pipe would otherwise wait for a writer before it could be refused.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw UserError("cannot open snapshot '" + path + "': " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw UserError("snapshot '" + path + "' " + not_a_file(path));
  }
  auto m = std::make_shared<Mapping>();
  m->length = static_cast<std::size_t>(st.st_size);
  if (m->length > 0) {
    void* a = ::mmap(nullptr, m->length, PROT_READ, MAP_PRIVATE, fd, 0);
    if (a == MAP_FAILED) {
      const int err = errno;
      ::close(fd);
      throw UserError("cannot read snapshot '" + path + "': " + std::strerror(err));
    }
    m->address = a;
    ::madvise(a, m->length, MADV_SEQUENTIAL);
  }
  ::close(fd);
  MappedFile f;
  f.path_ = path;
  f.data_ = static_cast<const char*>(m->address);
  f.size_ = m->length;
  f.mapping_ = std::move(m);
  return f;
}

MappedFile MappedFile::from_bytes(std::string name, std::string bytes) {
  auto m = std::make_shared<Mapping>();
  m->owned = std::move(bytes);
  MappedFile f;
  f.path_ = std::move(name);
  f.data_ = m->owned.data();
  f.size_ = m->owned.size();
  f.mapping_ = std::move(m);
  return f;
}

}  // namespace gs
