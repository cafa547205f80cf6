#include "apps/plot.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "apps/cli.h"

namespace gs::app {

std::string gnuplot_preamble(const std::string& png, int width, int height) {
  std::ostringstream s;
  s << "# Restyle freely and rerun: gnuplot " << png.substr(0, png.size() - 4) << ".gp\n"
    << "set terminal pngcairo size " << width << "," << height
    << " enhanced font 'DejaVu Sans,12'\n"
    << "set output '" << png << "'\n"
    << "set datafile separator ','\n"
    << "set key top left box opaque\n"
    << "set grid\n"
    << "set style data linespoints\n"
    << "set pointsize 0.8\n";
  return s.str();
}

std::string run_gnuplot(const std::filesystem::path& dir, const std::string& name,
                        const std::string& script) {
  write_file_atomic(dir / name, script);
  const auto abs = std::filesystem::absolute(dir);
  const auto log = abs / (name + ".log");
  const std::string cmd =
      "cd '" + abs.string() + "' && gnuplot '" + name + "' >'" + log.string() + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  std::string first;
  {
    std::ifstream f(log);
    std::getline(f, first);
  }
  if (rc == 0) {
    std::filesystem::remove(log);
    return {};
  }
  return "gnuplot " + name + " failed (" + (first.empty() ? "is gnuplot installed?" : first) + ")";
}

}  // namespace gs::app
