#pragma once
// Gzip-compressed snapshot files (NAME.xyz.gz, dump.lammpstrj.gz, as ASE, OVITO and LAMMPS read
// them), told by their magic bytes, not their name. The readers index and parse a file in place,
// so a compressed one is inflated into memory once (zlib); its size is bounded as it grows, so
// a small file that would inflate past the bound (a decompression bomb) is refused in one line.
#include <cstddef>
#include <string>
#include <string_view>

namespace gs {

// Whether `bytes` begin as a gzip member does (RFC 1952: 1f 8b, then deflate).
bool is_gzip(std::string_view bytes);

// The inflated contents of every gzip member in `bytes` (`cat a.gz b.gz` is a valid file).
// UserError naming `name` when the data are corrupt, cut short, or inflate past `max_bytes`.
std::string gunzip(std::string_view bytes, const std::string& name, std::size_t max_bytes);

// The bound for input files: half of this machine's memory.
std::size_t gunzip_limit();

}  // namespace gs
