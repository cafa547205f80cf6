#include "io/output_dir.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string_view>
#include <vector>

#include "sim/error.h"

namespace gs {

std::filesystem::path prepare_output_dir(const std::string& dir, bool force,
                                         std::span<const char* const> replaced) {
  namespace fs = std::filesystem;
  const fs::path p(dir);
  std::error_code ec;
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) throw UserError("--out " + dir + ": exists and is not a folder");
    if (!fs::is_empty(p, ec) && !force)
      throw UserError("--out " + dir +
                      ": folder exists and is not empty (use --force to write into it)");
  } else {
    fs::create_directories(p, ec);
    if (ec) throw UserError("--out " + dir + ": cannot create folder: " + ec.message());
  }
  // Two commands given the same new folder may both have found it absent or empty: the first
  // to lock it writes, and the second, once it holds the lock, finds the first one's files.
  lock_output_dir(p);
  if (!force && !fs::is_empty(p, ec))
    throw UserError("--out " + dir +
                    ": another grainshock process wrote into this folder meanwhile (use "
                    "--force to write into it)");
  for (const char* name : replaced) {
    fs::remove_all(p / name, ec);
    if (ec)
      throw UserError("--force: cannot remove '" + (p / name).string() + "': " + ec.message());
  }
  return p;
}

void lock_output_dir(const std::filesystem::path& dir) {
  static std::vector<std::string> held;  // one lock per folder and process, kept to the end
  const std::string key = std::filesystem::weakly_canonical(dir).string();
  if (std::find(held.begin(), held.end(), key) != held.end()) return;
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw UserError("cannot open '" + dir.string() + "': " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    throw UserError("'" + dir.string() + "' is in use by another grainshock process");
  }
  held.push_back(key);
}

void remove_leftovers(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  auto digits = [](std::string_view s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos;
  };
  for (const fs::path& sub : {dir, dir / "snapshots", dir / "frames"}) {
    std::error_code ec;
    std::vector<fs::path> doomed;
    for (const auto& entry : fs::directory_iterator(sub, ec)) {
      const std::string name = entry.path().filename().string();
      const auto tmp = name.rfind(".tmp.");
      const bool atomic =
          tmp != std::string::npos && digits(std::string_view(name).substr(tmp + 5));
      bool movie = false;
      if (name.starts_with(".") && name.ends_with(".partial")) {
        const std::string_view stem = std::string_view(name).substr(0, name.size() - 8);
        movie = digits(stem.substr(stem.rfind('.') + 1));
      }
      if ((atomic || movie) && entry.is_regular_file(ec)) doomed.push_back(entry.path());
    }
    for (const auto& p : doomed) fs::remove(p, ec);
  }
}

}  // namespace gs
