// grainshock compare EXPECTED ACTUAL: golden-image tests of PNGs and movies on the command line,
// by the rule of render/image_compare.h.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/exit_code.h"
#include "io/atomic_file.h"
#include "io/mapped_file.h"
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
  if (const std::string why = not_a_file(path); !why.empty()) trouble("'" + path + "': " + why);
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

// Why alike or not: the largest blob that neither picture explains from the other, then the
// totals and the summaries.
std::string figures(const CompareCommand& o, const render::ImageComparison& c) {
  const render::Blob& b = c.largest;
  std::string t;
  if (c.blobs == 0) {
    t = "no pixel off its neighbours' blends by more than " +
        std::to_string(o.compare.channel_tolerance);
  } else {
    t = "worst blob " + std::to_string(b.pixels) + " px (" + std::to_string(c.max_pixels) +
        " allowed), mass " + std::to_string(b.mass) + " (" + std::to_string(c.max_mass) +
        " allowed), at x " + std::to_string(b.x0) + "-" + std::to_string(b.x1) + ", y " +
        std::to_string(b.y0) + "-" + std::to_string(b.y1) + ", off by up to " +
        std::to_string(b.peak) + " (tolerance " + std::to_string(o.compare.channel_tolerance) +
        "); " + std::to_string(c.differing) + " px in " + std::to_string(c.blobs) +
        (c.blobs == 1 ? " blob" : " blobs");
  }
  return t + "; largest channel difference " + std::to_string(c.max_channel_difference) +
         ", PSNR " + psnr_text(c.psnr) + " dB, SSIM " + number("%.4f", c.ssim);
}

// What the rule cannot see, from the disc radius the renderer recorded in each PNG's text: the
// renderer knows it exactly, where a size guessed from the pixels fails on touching discs, a
// dense band or discs coloured near the background. Empty when both record discs of at least
// kSmallestSeenDiscPx, or neither records any (another program's picture).
std::string blindness(const CompareCommand& o) {
  std::vector<std::pair<const std::string*, double>> small;
  for (const std::string* path : {&o.expected, &o.actual}) {
    const std::optional<double> r = render::disc_radius_of(render::read_png_text(*path));
    if (r && *r < render::kSmallestSeenDiscPx) small.emplace_back(path, *r);
  }
  if (small.empty()) return {};
  std::string t = "blind to one particle: ";
  if (small.size() == 2 && number("%.3g", small[0].second) == number("%.3g", small[1].second))
    t += "both have discs of " + number("%.3g", small[0].second) + " px radius";
  else
    for (std::size_t k = 0; k < small.size(); ++k)
      t += (k ? ", " : "") + *small[k].first + " has discs of " +
           number("%.3g", small[k].second) + " px radius";
  return t + ", below the " + number("%.3g", render::kSmallestSeenDiscPx) +
         " px this rule needs to see one particle move (draw them larger: --centre and --zoom, "
         "--slab, a larger picture)";
}

Outcome compare_pngs(const CompareCommand& o) {
  const Image e = render::read_png(o.expected), a = render::read_png(o.actual);
  check_sizes(o, e.width, e.height, a.width, a.height);
  const render::ImageComparison c = render::compare_images(e, a, o.compare);
  const std::string blind = blindness(o);
  Outcome out{c.match(), (blind.empty() ? "" : blind + "; ") + figures(o, c), {}};
  if (!o.diff.empty()) out.diff = render::diff_image(e, a, o.compare);
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
      out.diff = render::diff_image(fe, fa, o.compare);
  }
  while (e.next()) {
  }
  while (a.next()) {
  }
  out.match = s.match();
  // The worst frame's figures, with PSNR and SSIM over the whole movie.
  render::ImageComparison summary = s.worst;
  summary.max_channel_difference = s.max_channel_difference;
  summary.psnr = s.psnr();
  summary.ssim = s.mean_ssim();
  out.line = (s.same_count ? ""
                           : std::to_string(e.frames_read()) + " frames against " +
                                 std::to_string(a.frames_read()) + "; ") +
             "worst frame " + std::to_string(s.worst_frame) + " of " + std::to_string(s.frames) +
             " compared: " + figures(o, summary) +
             " (largest channel difference, PSNR and SSIM over all frames)";
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
                  "A pixel differs when R, G or B lies further than this (of 255) from every "
                  "blend of the other picture's pixel with a neighbour")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  sub->add_option("--max-blob", o->compare.max_blob_pixels,
                  "Alike when no connected group of differing pixels has more than this many "
                  "(per frame)")
      ->check(CLI::Range(0L, 1L << 40))
      ->capture_default_str();
  sub->add_option("--max-mass", o->compare.max_blob_mass,
                  "Alike when no blob's differences beyond the tolerance sum to more than this "
                  "(levels x pixels, per frame)")
      ->check(CLI::Range(0L, 1L << 40))
      ->capture_default_str();
  sub->add_option("--diff", o->diff,
                  "Write a PNG (NAME.png) with the differing pixels in red (a movie's worst frame)")
      ->check(png_name());
  sub->add_flag("--update", o->update,
                "Copy ACTUAL to EXPECTED when EXPECTED is missing or not alike; exit 0");
  sub->footer(
      "Prints one line: alike or not alike; \"blind to one particle\" when a PNG drawn by "
      "grainshock records discs under 1.5 px radius (too small for the rule to see one particle "
      "move); the largest blob of differing pixels (size, place, how far off), the totals, the "
      "largest plain channel difference, PSNR (over R, G, B) and SSIM (Wang et al. 2004, BT.709 "
      "luma, 11x11 Gaussian window). Exit 0 alike, 1 not alike, 2 bad input (missing file, "
      "different sizes, not a PNG or movie).");
  sub->callback([o] {
    try {
      compare(*o);
    } catch (const UserError& e) {  // an unreadable PNG, a broken movie, an unwritable --diff
      trouble(e.what());
    }
  });
}

}  // namespace gs::app
