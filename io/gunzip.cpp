#include "io/gunzip.h"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "sim/error.h"
#include "sim/stop.h"

namespace gs {

bool is_gzip(std::string_view b) {
  return b.size() >= 3 && static_cast<unsigned char>(b[0]) == 0x1f &&
         static_cast<unsigned char>(b[1]) == 0x8b && b[2] == 8;
}

std::string gunzip(std::string_view bytes, const std::string& name, std::size_t max_bytes) {
  const std::string where = "snapshot '" + name + "'";
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK)  // 16 +: a gzip wrapper, not zlib's
    throw UserError(where + ": zlib cannot start to inflate it");
  // inflateEnd on every way out, errors included.
  struct End {
    z_stream& z;
    ~End() { inflateEnd(&z); }
  } end{z};
  std::string out;
  constexpr std::size_t kChunk = std::size_t{1} << 18;
  std::size_t in = 0;
  while (true) {
    throw_if_stopped();  // gigabytes take seconds
    if (out.size() > max_bytes) {
      char limit[32];
      std::snprintf(limit, sizeof limit, "%.3g GB", static_cast<double>(max_bytes) / 1e9);
      throw UserError(where + ": inflates to more than " + limit +
                      " (half of this machine's memory); gunzip it first");
    }
    const std::size_t have = out.size();
    out.resize(have + kChunk);
    const std::size_t feed =
        std::min<std::size_t>(bytes.size() - in, std::numeric_limits<uInt>::max());
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + in));
    z.avail_in = static_cast<uInt>(feed);
    z.next_out = reinterpret_cast<Bytef*>(out.data() + have);
    z.avail_out = static_cast<uInt>(kChunk);
    const int rc = inflate(&z, Z_NO_FLUSH);
    in += feed - z.avail_in;
    out.resize(have + (kChunk - z.avail_out));
    if (rc == Z_STREAM_END) {
      // Another member may follow; zeros after the last are padding (tape blocks).
      const std::string_view rest = bytes.substr(in);
      if (rest.find_first_not_of('\0') == std::string_view::npos) break;
      if (!is_gzip(rest))
        throw UserError(where + ": data after the end of its gzip stream are not gzip");
      inflateReset(&z);
      continue;
    }
    if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT)
      throw UserError(where + ": corrupt gzip data (" + (z.msg ? z.msg : "invalid data") + ")");
    if (rc == Z_MEM_ERROR) throw UserError(where + ": out of memory while inflating it");
    // No progress with all the input given: the stream ends before its end marker.
    if (rc == Z_BUF_ERROR || (in == bytes.size() && z.avail_out > 0 && rc == Z_OK))
      throw UserError(where + ": cut short (the gzip data end before the stream does)");
    if (rc != Z_OK) throw UserError(where + ": zlib error " + std::to_string(rc));
  }
  out.shrink_to_fit();
  return out;
}

std::size_t gunzip_limit() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::size_t{8} << 30;
  return static_cast<std::size_t>(pages) / 2 * static_cast<std::size_t>(page);
}

}  // namespace gs
