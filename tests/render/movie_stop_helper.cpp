// Test helper: writes frames into argv[1] until SIGINT/SIGTERM, then finishes the movie the way
// `grainshock movie` does. Prints "ready" after 20 frames and "frames N" at the end; exits with
// 128 + the signal.
#include <cstdio>

#include "render/movie_writer.h"
#include "sim/stop.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  gs::install_stop_handlers();
  gs::render::MovieOptions o;
  o.width = 64;
  o.height = 48;
  gs::render::MovieWriter movie(argv[1], o);
  int k = 0;
  // The bound keeps a lost signal from running forever; the test then fails on the exit code.
  for (; k < 100000 && !gs::stop_requested(); ++k) {
    gs::render::Image img(o.width, o.height);
    for (std::size_t i = 0; i < img.rgba.size(); ++i)
      img.rgba[i] = static_cast<std::uint8_t>(i % 4 == 3 ? 255 : (i / 4 + 3 * k) % 256);
    movie.add(std::move(img));
    if (k + 1 == 20) {
      std::printf("ready\n");
      std::fflush(stdout);
    }
  }
  movie.finish();
  std::printf("frames %d\n", k);
  return gs::stop_requested() ? 128 + gs::stop_signal() : 0;
}
