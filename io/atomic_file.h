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

}  // namespace gs
