// grainshock compare EXPECTED ACTUAL: golden-image tests of PNGs and movies on the command line,
// by the rule of render/image_compare.h.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "apps/commands.h"
#include "apps/exit_code.h"
#include "io/atomic_file.h"
#include "render/image_compare.h"
#include "render/movie_reader.h"
#include "render/png.h"
#include "sim/error.h"

namespace gs::app {
namespace {

namespace fs = std::filesystem;
using render::CompareOptions;
using render::Image;

struct CompareCommand {
  std::string expected, actual, diff;
  bool update = false;
  CompareOptions compare;
};

enum class Kind { Png, Movie };

// Bad input of compare exits 2 (as with cmp and diff), not 1, which means "not alike".
[[noreturn]] void trouble(const std::string& what) {
  throw CodedError(kExitCompareTrouble, what);
}

// Chosen by content: the PNG signature, else whatever libavformat recognises as video.
Kind kind_of(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) trouble("'" + path + "': no such file");
  char sig[8] = {};
  std::ifstream(path, std::ios::binary).read(sig, sizeof sig);
  if (std::string(sig, 8) == "\x89PNG\r\n\x1a\n") return Kind::Png;
  try {
    render::MovieReader probe(path);
    return Kind::Movie;
  } catch (const UserError& e) {
    trouble("'" + path + "' is not a PNG or a movie (" + e.what() + ")");
  }
}

std::string size_text(int w, int h) {
  return std::to_string(w) + "x" + std::to_string(h);
}

void check_sizes(const CompareCommand& o, int we, int he, int wa, int ha) {
  if (we != wa || he != ha)
    trouble("sizes differ: " + o.expected + " is " + size_text(we, he) + ", " + o.actual + " is " +
            size_text(wa, ha));
}

std::string number(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string psnr_text(double db) {
  return std::isinf(db) ? "inf" : number("%.2f", db);
}

struct Outcome {
  bool match = false;
  std::string line;           // the figures, after "alike: " or "not alike: "
  std::optional<Image> diff;  // of the picture, or of the movie's worst frame
};

std::string figures(const CompareCommand& o, double fraction, int max_diff, double psnr,
                    double ssim) {
  return number("%.4g", 100 * fraction) + "% of pixels differ by more than " +
         std::to_string(o.compare.channel_tolerance) + " (" +
         number("%.4g", 100 * o.compare.max_differing_fraction) +
         "% allowed), largest channel difference " + std::to_string(max_diff) + ", PSNR " +
         psnr_text(psnr) + " dB, SSIM " + number("%.4f", ssim);
}

Outcome compare_pngs(const CompareCommand& o) {
  const Image e = render::read_png(o.expected), a = render::read_png(o.actual);
  check_sizes(o, e.width, e.height, a.width, a.height);
  const render::ImageComparison c = render::compare_images(e, a, o.compare);
  Outcome out{
      c.match(), figures(o, c.differing_fraction(), c.max_channel_difference, c.psnr, c.ssim), {}};
  if (!o.diff.empty()) out.diff = render::diff_image(e, a, o.compare.channel_tolerance);
  return out;
}

Outcome compare_movies(const CompareCommand& o) {
  render::MovieReader e(o.expected), a(o.actual);
  check_sizes(o, e.info().width, e.info().height, a.info().width, a.info().height);
  render::SequenceComparison s;
  Outcome out;
  for (;;) {
    const bool more_e = e.next(), more_a = a.next();
    if (more_e != more_a) s.same_count = false;
    if (!more_e || !more_a) break;
    const Image fe = e.rgb(), fa = a.rgb();
    check_sizes(o, fe.width, fe.height, fa.width, fa.height);
    const int worst = s.worst_frame;
    s.add(render::compare_images(fe, fa, o.compare));
    if (!o.diff.empty() && s.worst_frame != worst)
      out.diff = render::diff_image(fe, fa, o.compare.channel_tolerance);
  }
  while (e.next()) {
  }
  while (a.next()) {
  }
  out.match = s.match();
  out.line = (s.same_count ? ""
                           : std::to_string(e.frames_read()) + " frames against " +
                                 std::to_string(a.frames_read()) + "; ") +
             figures(o, s.worst_fraction, s.max_channel_difference, s.psnr(), s.mean_ssim()) +
             " (worst frame " + std::to_string(s.worst_frame) + " of " + std::to_string(s.frames) +
             " compared; PSNR and SSIM over all)";
  return out;
}

// EXPECTED becomes a byte copy of ACTUAL, atomically, so an interrupted update leaves the old one.
void copy_to_expected(const CompareCommand& o) {
  std::ifstream in(o.actual, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw UserError("cannot read '" + o.actual + "'");
  write_file_atomic(o.expected, bytes.str());
}

void compare(const CompareCommand& o) {
  const Kind ka = kind_of(o.actual);
  if (!fs::exists(o.expected)) {
    if (!o.update) trouble("'" + o.expected + "': no such file (--update creates it from ACTUAL)");
    copy_to_expected(o);
    std::printf("created %s from %s\n", o.expected.c_str(), o.actual.c_str());
    return;
  }
  const Kind ke = kind_of(o.expected);
  if (ke != ka)
    trouble(o.expected + " is a " + (ke == Kind::Png ? "PNG" : "movie") + " but " + o.actual +
            " is a " + (ka == Kind::Png ? "PNG" : "movie"));
  const Outcome r = ka == Kind::Png ? compare_pngs(o) : compare_movies(o);
  std::printf("%s: %s\n", r.match ? "alike" : "not alike", r.line.c_str());
  if (r.diff) render::write_png(o.diff, *r.diff);
  if (r.match) return;
  if (o.update) {
    copy_to_expected(o);
    std::printf("updated %s from %s\n", o.expected.c_str(), o.actual.c_str());
    return;
  }
  std::fflush(stdout);
  throw Exit{kExitNotAlike};
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareCommand>();
  auto* sub = app.add_subcommand(
      "compare", "Compare two PNGs, or two movies frame by frame (golden-image tests)");
  sub->add_option("EXPECTED", o->expected, "The reference picture or movie")->required();
  sub->add_option("ACTUAL", o->actual, "The picture or movie to check")->required();
  sub->add_option("--tolerance", o->compare.channel_tolerance,
                  "A pixel differs when R, G or B differs by more than this (of 255)")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  sub->add_option("--max-fraction", o->compare.max_differing_fraction,
                  "Alike when at most this fraction of the pixels differ (per frame)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("--diff", o->diff,
                  "Write a PNG with the differing pixels in red (a movie's worst frame)");
  sub->add_flag("--update", o->update,
                "Copy ACTUAL to EXPECTED when EXPECTED is missing or not alike; exit 0");
  sub->footer(
      "Prints one line: alike or not alike, the fraction of differing pixels, the largest channel "
      "difference, PSNR (over R, G, B) and SSIM (Wang et al. 2004, BT.709 luma, 11x11 Gaussian "
      "window). Exit 0 alike, 1 not alike, 2 bad input (missing file, different sizes, not a PNG "
      "or movie).");
  sub->callback([o] {
    try {
      compare(*o);
    } catch (const UserError& e) {  // an unreadable PNG, a broken movie, an unwritable --diff
      trouble(e.what());
    }
  });
}

}  // namespace gs::app
