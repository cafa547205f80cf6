// Uses the installed grainshock libraries: kicks one disc of a 2D gas at rest, runs to t = 2000
// and draws the disturbed particles coloured by speed. Usage: kick_and_render OUT.png
#include <cstdio>

#include "render/png.h"
#include "render/renderer.h"
#include "sim/engine.h"
#include "sim/error.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.png\n", argv[0]);
    return 2;
  }
  try {
    gs::PhysicsConfig c;  // the paper's 2D gas, smaller
    c.particles = 4000;
    c.t_max = 2000;
    gs::validate(c);
    auto sim = gs::make_simulation(c);
    sim->run_until(c.t_max);
    const gs::Snapshot s = sim->snapshot();
    gs::render::View view;
    view.width = 480, view.height = 360;
    gs::render::Renderer renderer;
    gs::render::write_png(argv[1], renderer.render(s, gs::render::Style{}, view));
    std::printf("t = %g: %lld collisions, picture in %s\n", sim->time(),
                static_cast<long long>(sim->stats().collisions), argv[1]);
  } catch (const gs::UserError& e) {
    std::fprintf(stderr, "kick_and_render: %s\n", e.what());
    return 1;
  }
}
