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

MappedFile MappedFile::open(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw UserError("cannot open snapshot '" + path + "': " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw UserError("snapshot '" + path + "' is not a regular file");
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
