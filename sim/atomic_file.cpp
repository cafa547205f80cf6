#include "sim/atomic_file.h"

#include <unistd.h>

#include <fstream>
#include <string>

#include "sim/error.h"

namespace gs {

void write_file_atomic(const std::filesystem::path& path, std::string_view text) {
  namespace fs = std::filesystem;
  // The pid keeps two processes writing the same file from sharing a temporary.
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid());
  std::error_code ec;
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (f) f.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (f) f.close();
    if (!f) {
      fs::remove(tmp, ec);
      throw UserError("cannot write '" + path.string() + "'");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw UserError("cannot write '" + path.string() + "': " + why);
  }
}

}  // namespace gs
