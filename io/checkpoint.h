#pragma once
// Checkpoint files: the exact state of a run, binary, so that a resumed run continues the very
// same history. A fixed header says what wrote the file (magic, format version, program version,
// instruction set, dimension, particles) and holds the payload's length and checksum, so that a
// file from another build, a truncated one and a corrupt one are each told apart and refused
// before anything is read into an engine. The payload is whatever the writers put, read back in
// the same order.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/state_stream.h"

namespace gs {

// The instruction set this build was compiled for. Histories are the same on every x86-64 build
// (FMA stays off), but the packed engine records follow Eigen's alignment for it.
const char* instruction_set();

// Streams a checkpoint into `path` through a temporary beside it; commit() renames an existing
// `path` to `previous` first, so that a kill at any moment leaves one whole checkpoint at least.
class CheckpointWriter final : public StateWriter {
 public:
  CheckpointWriter(const std::filesystem::path& path, const std::filesystem::path& previous,
                   const StateIdentity& id);
  ~CheckpointWriter() override;
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  void bytes(const void* p, std::size_t n) override;
  // Writes what is buffered, the length and the checksum: the file is whole but neither on
  // disk for sure nor in place. Nothing can be added after.
  void finish();
  // finish(), then syncs and puts the file in place. Throws UserError naming the file and the
  // OS reason; then nothing replaces the earlier checkpoint. It touches only the file, so it may
  // run on another thread than the one that wrote the state.
  void commit();
  std::uint64_t size() const { return written_; }

 private:
  void flush();
  void write_all(const void* p, std::size_t n);
  std::filesystem::path path_, previous_, tmp_;
  int fd_ = -1;
  std::vector<unsigned char> buffer_;
  std::uint64_t written_ = 0, hash_ = 0;
  bool finished_ = false;
};

// The checksum of a whole file, as checkpoints take theirs; UserError naming the file and the OS
// reason if it cannot be read.
std::uint64_t file_checksum(const std::filesystem::path& path);

// The checkpoint to resume from: `path`, else `previous` (a kill between the two renames of a
// commit leaves only that one). UserError "'FOLDER' holds no WHAT (NAME) to resume from" when
// neither exists.
std::filesystem::path checkpoint_to_resume(const std::filesystem::path& path,
                                           const std::filesystem::path& previous,
                                           const std::string& what);

// Reads a whole checkpoint, refusing (UserError, one line naming the file) a file that is not
// one, from another format, program version or instruction set, truncated, or corrupt.
class CheckpointReader final : public StateReader {
 public:
  explicit CheckpointReader(const std::filesystem::path& path);
  ~CheckpointReader() override;
  CheckpointReader(const CheckpointReader&) = delete;
  CheckpointReader& operator=(const CheckpointReader&) = delete;

  const StateIdentity& identity() const override { return id_; }
  void bytes(void* p, std::size_t n) override;
  // Throws unless the payload has been read to its end exactly.
  void finish() const;

 private:
  std::size_t remaining() const override { return size_ - pos_; }
  [[noreturn]] void corrupt() const override;
  std::filesystem::path path_;
  StateIdentity id_;
  const unsigned char* data_ = nullptr;
  std::size_t size_ = 0, pos_ = 0, mapped_ = 0;
};

}  // namespace gs
