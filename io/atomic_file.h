#pragma once
#include <filesystem>
#include <initializer_list>
#include <string_view>

namespace gs {

// Writes `text` to `path` through a temporary file beside it and a rename, so a reader never
// sees half a file and a failed or interrupted write leaves the earlier version intact.
// Failures are UserErrors naming the path.
void write_file_atomic(const std::filesystem::path& path, std::string_view text);
// The same for a file made of pieces, written one after the other (no joined copy of a big file).
void write_file_atomic(const std::filesystem::path& path,
                       std::initializer_list<std::string_view> pieces);

// The same for a file written piece by piece (a trajectory of many frames, never whole in
// memory): pieces go to a temporary beside `path`; finish() may overwrite its first bytes (a
// header known only at the end) and renames it. Destroyed unfinished, the temporary is removed.
class AtomicFileWriter {
 public:
  AtomicFileWriter() = default;
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  void open(const std::filesystem::path& path);
  void write(std::string_view piece);
  void finish(std::string_view head = {});

 private:
  [[noreturn]] void fail(const std::string& why);
  std::filesystem::path path_, tmp_;
  int fd_ = -1;
};

}  // namespace gs
