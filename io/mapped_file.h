#pragma once
// The bytes of an input file, memory-mapped read-only so that a reader can index a file of many
// frames in one scan and parse one frame at a time without copying it or keeping the others:
// the pages are the kernel's page cache, not this process's heap. As with any mapping, a file cut
// short in place while it is read ends the process with SIGBUS. A file that grows (LAMMPS and
// gsd append frames) or is replaced by a rename (as the writers here do) is read safely.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace gs {

// Why `path` cannot be read as a file, for a message: "no such file", "is a directory", "is a
// pipe (not a regular file)", ...; empty for a regular file (symbolic links followed).
std::string not_a_file(const std::filesystem::path& path);

class MappedFile {
 public:
  // UserError naming the path if it cannot be opened or is not a regular file.
  static MappedFile open(const std::string& path);
  // The same over bytes held in memory (tests, fuzzing); `name` stands for the path in errors.
  static MappedFile from_bytes(std::string name, std::string bytes);

  const std::string& path() const { return path_; }
  std::string_view bytes() const { return {data_, size_}; }

 private:
  struct Mapping;
  std::string path_;
  std::shared_ptr<const Mapping> mapping_;  // unmaps when the last copy goes
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace gs
