#include "jobs/plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/atomic_file.h"
#include "sim/error.h"

extern char** environ;

namespace gs::jobs {

std::vector<std::string> parse_plot_formats(const std::string& list) {
  std::vector<std::string> out;
  std::istringstream in(list);
  for (std::string f; std::getline(in, f, ',');) {
    if (f != "png" && f != "svg" && f != "pdf")
      throw UsageError("--format: unknown figure format '" + f + "' (png, svg, pdf)");
    if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  }
  if (out.empty()) throw UsageError("--format: no figure format given (png, svg, pdf)");
  return out;
}

std::string gnuplot_preamble(const std::string& base, int width, int height) {
  std::ostringstream s;
  s << "# Restyle freely and rerun: gnuplot " << base << ".gp (writes " << base
    << ".png; gnuplot -e \"format='svg'\" " << base << ".gp writes " << base << ".svg, 'pdf' "
    << base << ".pdf)\n"
    << "if (!exists('format')) format = 'png'\n"
    << "if (format eq 'svg') {\n"
    << "  set terminal svg size " << width << "," << height
    << " enhanced font 'DejaVu Sans,12' background rgb 'white'\n"
    << "} else {\n"
    << "  if (format eq 'pdf') {\n"
    // 72 points per inch: the PDF has the PNG's proportions of text to plot.
    << "    set terminal pdfcairo size " << width / 72.0 << "in," << height / 72.0
    << "in enhanced font 'DejaVu Sans,12'\n"
    << "  } else {\n"
    << "    set terminal pngcairo size " << width << "," << height
    << " enhanced font 'DejaVu Sans,12'\n"
    << "  }\n"
    << "}\n"
    << "set output '" << base << ".'.format\n"
    << "set encoding utf8\n"
    << "set datafile separator ','\n"
    // Room on the right for the last tick label of a log axis (10^5 and the like).
    << "set rmargin 5\n"
    << "set key top left box opaque\n"
    << "set grid\n"
    << "set style data linespoints\n"
    << "set pointsize 0.8\n";
  return s.str();
}

namespace {

// Runs gnuplot -e "format='FMT'" NAME in dir with stdout and stderr into log; the exit status
// or -1 (spawn failed, errno in `error`).
int spawn_gnuplot(const std::filesystem::path& dir, const std::string& name,
                  const std::string& format, const std::filesystem::path& log, int& error) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  const std::string e = "format='" + format + "'";
  std::string prog = "gnuplot", opt = "-e", script = name;
  char* argv[] = {prog.data(), opt.data(), const_cast<char*>(e.c_str()), script.data(), nullptr};
  pid_t pid = 0;
  error = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

std::string run_gnuplot(const std::filesystem::path& dir, const std::string& name,
                        const std::string& script, const std::vector<std::string>& formats) {
  write_file_atomic(dir / name, script);
  const auto abs = std::filesystem::absolute(dir);
  const auto log = abs / (name + ".log");
  for (const auto& format : formats) {
    int error = 0;
    const int rc = spawn_gnuplot(abs, name, format, log, error);
    if (rc == -1)
      return "gnuplot " + name + " not run (" + std::strerror(error) + "; is gnuplot installed?)";
    std::string first;
    {
      std::ifstream f(log);
      std::getline(f, first);
    }
    if (rc != 0)
      return "gnuplot " + name + " failed for " + format + " (" +
             (first.empty() ? "exit status " + std::to_string(rc) : first) + ")";
  }
  std::filesystem::remove(log);
  return {};
}

}  // namespace gs::jobs
