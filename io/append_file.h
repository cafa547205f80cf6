#pragma once
// A file written in whole records, like the rows of timeseries.csv: every write is checked and a
// failure names the file and the OS reason ("No space left on device"), and a record the disk
// took only part of is cut off again, so that the file never ends in the middle of a row.
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace gs {

class AppendFile {
 public:
  // Opens `path` keeping its first `keep` bytes (0: a new, empty file). Refuses (UserError) a
  // file shorter than `keep`: it is not the file the caller knew.
  AppendFile(const std::filesystem::path& path, std::uint64_t keep);
  ~AppendFile();
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;

  void append(std::string_view record);
  std::uint64_t size() const { return size_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

}  // namespace gs
