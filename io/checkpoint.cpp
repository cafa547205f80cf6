#include "io/checkpoint.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "io/mapped_file.h"
#include "sim/error.h"

namespace gs {
namespace {

constexpr char kMagic[8] = {'G', 'S', 'C', 'H', 'K', 'P', 'T', '\n'};
// Bumped whenever what any writer puts changes (2: the resting store, sim/resting_store.h; 3:
// singly linked cell lists, no list of moved records in a box kick).
constexpr std::uint32_t kFormat = 3;
constexpr std::size_t kChunk = std::size_t{4} << 20;  // the checksum is taken chunk by chunk

struct Header {
  char magic[8];
  std::uint32_t format;
  std::uint32_t dim;
  std::uint64_t particles;
  char version[32];
  char isa[32];
  std::uint64_t payload_bytes;
  std::uint64_t checksum;
};

std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

constexpr std::uint64_t kP1 = 0x9E3779B185EBCA87ULL, kP2 = 0xC2B2AE3D27D4EB4FULL;

// A word-wise checksum in four independent lanes (the mixing of xxHash64, not its exact
// algorithm): a few GB/s, so that checksumming a 2e6-sphere state takes a small part of the
// write. It detects corruption; it is no defence against forgery.
std::uint64_t chunk_hash(const unsigned char* p, std::size_t n, std::uint64_t seed) {
  std::uint64_t h[4] = {seed + kP1 + kP2, seed + kP2, seed, seed - kP1};
  std::size_t i = 0;
  for (; i + 32 <= n; i += 32)
    for (int l = 0; l < 4; ++l) {
      std::uint64_t w;
      std::memcpy(&w, p + i + 8 * l, 8);
      h[l] = rotl(h[l] + w * kP2, 31) * kP1;
    }
  std::uint64_t x = n;
  for (int l = 0; l < 4; ++l) x = rotl(x ^ h[l], 27) * kP1 + kP2;
  for (; i < n; ++i) x = rotl(x ^ (p[i] * kP1), 11) * kP2;
  x ^= x >> 33;
  x *= kP2;
  x ^= x >> 29;
  x *= kP1;
  return x ^ (x >> 32);
}

std::string os_reason() {
  return std::strerror(errno);
}

void copy_field(char (&dst)[32], const char* src) {
  std::memset(dst, 0, sizeof dst);
  std::strncpy(dst, src, sizeof dst - 1);
}

std::string field(const char (&f)[32]) {
  return std::string(f, strnlen(f, sizeof f));
}

}  // namespace

std::uint64_t file_checksum(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw UserError("cannot read '" + path.string() + "': " + os_reason());
  std::vector<unsigned char> chunk(kChunk);
  std::uint64_t hash = 0;
  for (;;) {
    std::size_t got = 0;
    while (got < kChunk) {
      const ssize_t n = ::read(fd, chunk.data() + got, kChunk - got);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const std::string why = os_reason();
        ::close(fd);
        throw UserError("cannot read '" + path.string() + "': " + why);
      }
      if (n == 0) break;
      got += static_cast<std::size_t>(n);
    }
    if (got > 0) hash = chunk_hash(chunk.data(), got, hash);
    if (got < kChunk) break;
  }
  ::close(fd);
  return hash;
}

std::filesystem::path checkpoint_to_resume(const std::filesystem::path& path,
                                           const std::filesystem::path& previous,
                                           const std::string& what) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) return path;
  if (std::filesystem::exists(previous, ec)) return previous;
  throw UserError("'" + path.parent_path().string() + "' holds no " + what + " (" +
                  path.filename().string() + ") to resume from");
}

const char* instruction_set() {
#if defined(__x86_64__) && defined(__AVX2__)
  return "x86-64-v3";
#elif defined(__x86_64__)
  return "x86-64";
#elif defined(__aarch64__)
  return "aarch64";
#else
  return "unknown";
#endif
}

CheckpointWriter::CheckpointWriter(const std::filesystem::path& path,
                                   const std::filesystem::path& previous, const StateIdentity& id)
    : path_(path), previous_(previous) {
  tmp_ = path;
  tmp_ += ".tmp." + std::to_string(::getpid());
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw UserError("cannot write '" + tmp_.string() + "': " + os_reason());
  buffer_.reserve(kChunk);
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.format = kFormat;
  h.dim = static_cast<std::uint32_t>(id.dim);
  h.particles = id.particles;
  copy_field(h.version, GRAINSHOCK_VERSION);
  copy_field(h.isa, instruction_set());
  write_all(&h, sizeof h);  // length and checksum come at commit()
}

CheckpointWriter::~CheckpointWriter() {
  if (fd_ >= 0) {  // not committed: an error on the way
    ::close(fd_);
    ::unlink(tmp_.c_str());
  }
}

void CheckpointWriter::flush() {
  hash_ = chunk_hash(buffer_.data(), buffer_.size(), hash_);
  write_all(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void CheckpointWriter::write_all(const void* data, std::size_t left) {
  const auto* p = static_cast<const unsigned char*>(data);
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw UserError("cannot write '" + tmp_.string() + "': " + os_reason());
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void CheckpointWriter::bytes(const void* p, std::size_t n) {
  GS_CHECK(!finished_);
  const auto* c = static_cast<const unsigned char*>(p);
  written_ += n;
  while (n > 0) {
    // Whole chunks of a big array go from where they are: copying 300 MB into the buffer
    // would cost a tenth of a second for nothing. The checksum sees the same chunks.
    if (buffer_.empty() && n >= kChunk) {
      hash_ = chunk_hash(c, kChunk, hash_);
      write_all(c, kChunk);
      c += kChunk;
      n -= kChunk;
      continue;
    }
    const std::size_t take = std::min(n, kChunk - buffer_.size());
    buffer_.insert(buffer_.end(), c, c + take);
    c += take;
    n -= take;
    if (buffer_.size() == kChunk) flush();
  }
}

void CheckpointWriter::finish() {
  if (finished_) return;
  if (!buffer_.empty()) flush();
  const std::uint64_t tail[2] = {written_, hash_};
  if (::pwrite(fd_, tail, sizeof tail, offsetof(Header, payload_bytes)) != sizeof tail)
    throw UserError("cannot write '" + tmp_.string() + "': " + os_reason());
  finished_ = true;
}

void CheckpointWriter::commit() {
  finish();
  if (::fdatasync(fd_) != 0)
    throw UserError("cannot write '" + tmp_.string() + "': " + os_reason());
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const std::string why = os_reason();
    ::unlink(tmp_.c_str());
    throw UserError("cannot write '" + tmp_.string() + "': " + why);
  }
  std::error_code ec;
  if (std::filesystem::exists(path_, ec)) std::filesystem::rename(path_, previous_, ec);
  if (!ec) std::filesystem::rename(tmp_, path_, ec);
  if (ec) {
    ::unlink(tmp_.c_str());
    throw UserError("cannot write '" + path_.string() + "': " + ec.message());
  }
}

CheckpointReader::CheckpointReader(const std::filesystem::path& path) : path_(path) {
  const std::string name = "checkpoint '" + path.string() + "'";
  if (const std::string why = not_a_file(path); !why.empty())
    throw UserError("cannot read " + name + ": " + why);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw UserError("cannot read " + name + ": " + os_reason());
  struct stat st {};
  Header h{};
  const bool got = ::fstat(fd, &st) == 0 && static_cast<std::size_t>(st.st_size) >= sizeof h &&
                   ::pread(fd, &h, sizeof h, 0) == static_cast<ssize_t>(sizeof h);
  auto refuse = [&](const std::string& why) {
    ::close(fd);
    throw UserError(name + ": " + why);
  };
  if (!got) refuse("truncated (shorter than its header)");
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0) refuse("not a grainshock checkpoint");
  if (h.format != kFormat)
    refuse("format " + std::to_string(h.format) + ", this build reads format " +
           std::to_string(kFormat));
  if (field(h.version) != GRAINSHOCK_VERSION)
    refuse("written by grainshock " + field(h.version) + ", this is " + GRAINSHOCK_VERSION);
  if (field(h.isa) != instruction_set())
    refuse("written by a build for " + field(h.isa) + ", this build is for " + instruction_set());
  const auto file = static_cast<std::uint64_t>(st.st_size);
  if (file - sizeof h != h.payload_bytes)
    refuse(file - sizeof h < h.payload_bytes
               ? "truncated (" + std::to_string(file) + " of " +
                     std::to_string(h.payload_bytes + sizeof h) + " bytes)"
               : "longer than its header says (corrupt)");
  mapped_ = static_cast<std::size_t>(file);
  void* base = ::mmap(nullptr, mapped_, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (base == MAP_FAILED) throw UserError("cannot read " + name + ": " + os_reason());
  ::madvise(base, mapped_, MADV_SEQUENTIAL);
  data_ = static_cast<const unsigned char*>(base) + sizeof h;
  size_ = h.payload_bytes;
  std::uint64_t hash = 0;
  for (std::size_t at = 0; at < size_; at += kChunk)
    hash = chunk_hash(data_ + at, std::min(kChunk, size_ - at), hash);
  if (hash != h.checksum) {
    ::munmap(base, mapped_);
    data_ = nullptr;
    throw UserError(name + ": checksum failure (the file is corrupt)");
  }
  id_ = {static_cast<int>(h.dim), h.particles};
}

CheckpointReader::~CheckpointReader() {
  if (data_) ::munmap(const_cast<unsigned char*>(data_ - sizeof(Header)), mapped_);
}

void CheckpointReader::corrupt() const {
  throw UserError("checkpoint '" + path_.string() + "': inconsistent contents (corrupt)");
}

void CheckpointReader::bytes(void* p, std::size_t n) {
  if (n > remaining()) corrupt();
  if (n == 0) return;  // p may be an empty vector's null data(), which memcpy must not get
  std::memcpy(p, data_ + pos_, n);
  pos_ += n;
}

void CheckpointReader::finish() const {
  if (remaining() != 0) corrupt();
}

}  // namespace gs
