// Pictures of other programs' files: --color-by a numeric column the file has, or none (one
// colour), so that a file without velocities can be drawn; and `render` on bad files: one line
// naming the file and the line or frame, exit 1, no PNG.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/gsd.h"
#include "io/snapshot_file.h"
#include "render/field.h"
#include "render/image_compare.h"
#include "render/overlay.h"
#include "render/png.h"
#include "render/render_choices.h"
#include "render/scene.h"
#include "sim/error.h"
#include "tests/apps/cli_test_util.h"

namespace gs::render {
namespace {

namespace fs = std::filesystem;

OverlayPainter& painter() {
  static OverlayPainter p(Style{}.font);
  return p;
}

View view() {
  View v;
  v.width = 320;
  v.height = 240;
  return v;
}

// A row of 11 discs along x, no velocities, with a LAMMPS-like column c_pe = x and typeid.
Snapshot row_without_velocities() {
  Snapshot s;
  s.info.dim = 2;
  s.info.set_cubic_box(40);
  Column pe{"c_pe", {}}, type{"typeid", {}};
  for (int i = 0; i <= 10; ++i) {
    s.position.emplace_back(10 + 2 * i, 20, 0);
    s.radius.push_back(0.5);
    s.active.push_back(1);
    pe.values.push_back(i);
    type.values.push_back(i % 2);
  }
  s.columns = {pe, type};
  return s;
}

TEST(ColourBy, AColumnOfTheFileGivesTheShades) {
  const Snapshot s = row_without_velocities();
  Style st;
  st.field = choose_field("c_pe", s, "row.dump");
  ASSERT_EQ(st.field, Field::Column);
  st.column = "c_pe";
  st.range = std::pair{0.0, 10.0};
  const Scene sc = build_scene({&s}, st, view(), painter());
  EXPECT_EQ(sc.bar_label, "c_pe");
  ASSERT_EQ(sc.sprites.size(), s.size());
  // Sprites may be reordered for drawing; the disc at x = 10 + 2i has c_pe = i.
  const float x0 = std::min_element(sc.sprites.begin(), sc.sprites.end(), [](auto& a, auto& b) {
                     return a.x < b.x;
                   })->x;
  for (std::size_t k = 0; k < sc.sprites.size(); ++k) {
    const double i = std::round((sc.sprites[k].x - x0) / 2);
    EXPECT_NEAR(sc.shade[k], i / 10, 1e-6) << k;
  }
  // Without a fixed range, the percentiles of the column (1 to 99 of 0..10).
  st.range.reset();
  const Scene auto_sc = build_scene({&s}, st, view(), painter());
  EXPECT_NEAR(auto_sc.range.first, 0, 1e-12);
  EXPECT_NEAR(auto_sc.range.second, 10, 1e-12);
}

TEST(ColourBy, NoneDrawsOneColourWithoutABar) {
  const Snapshot s = row_without_velocities();
  Style st;
  st.field = choose_field("none", s, "row.dump");
  ASSERT_EQ(st.field, Field::None);
  const Scene sc = build_scene({&s}, st, view(), painter());
  EXPECT_FALSE(sc.style.colorbar);
  ASSERT_EQ(sc.sprites.size(), s.size());
  for (const Sprite& p : sc.sprites) EXPECT_EQ(std::memcmp(p.rgba, sc.sprites[0].rgba, 4), 0);
  for (float shade : sc.shade) EXPECT_EQ(shade, 0.5f);
}

// Types are categories: each particle in its type's colour of the palette (Okabe-Ito), a legend
// of the type names where the colour bar was.
TEST(ColourBy, TypesGetAPaletteAndALegendOfTheirNames) {
  Snapshot s = row_without_velocities();
  s.type_names = {"Ar", "He", "Ne"};
  for (std::size_t i = 0; i < s.size(); ++i) s.type.push_back(static_cast<std::uint32_t>(i % 3));
  std::string note;
  Style st;
  st.field = choose_field("auto", s, "row.xyz", &note);
  ASSERT_EQ(st.field, Field::Type) << "no velocities: type is the default";
  EXPECT_NE(note.find("no velocities: coloured by particle type"), std::string::npos) << note;
  const Scene sc = build_scene({&s}, st, view(), painter());
  EXPECT_FALSE(sc.style.colorbar);
  ASSERT_EQ(sc.legend.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(sc.legend[k].second, s.type_names[k]);
    EXPECT_EQ(sc.legend[k].first, overlay_colour(k));
  }
  ASSERT_EQ(sc.sprites.size(), s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Rgb8 want = overlay_colour(i % 3);
    EXPECT_EQ((Rgb8{sc.sprites[i].rgba[0], sc.sprites[i].rgba[1], sc.sprites[i].rgba[2]}), want)
        << "particle " << i;
  }
  // Without types, a file without velocities is drawn in one colour, and says so.
  const Snapshot plain = row_without_velocities();
  EXPECT_EQ(choose_field("auto", plain, "row.dump", &note), Field::None);
  EXPECT_NE(note.find("nothing (one colour)"), std::string::npos) << note;
}

TEST(ColourBy, UnknownOrMissingFieldsListWhatTheSnapshotHas) {
  const Snapshot s = row_without_velocities();
  for (const char* name : {"potential", "speed", "type"}) {
    try {
      choose_field(name, s, "row.dump");
      ADD_FAILURE() << name << " accepted";
    } catch (const UserError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("row.dump"), std::string::npos) << m;
      EXPECT_NE(m.find("none, c_pe, typeid"), std::string::npos) << m;
      EXPECT_EQ(m.find("scaled-speed"), std::string::npos) << "no velocities: " << m;
    }
  }
}

using test::CommandResult;
using test::scratch_dir;

CommandResult render(const std::string& args) {
  return test::grainshock("render " + args);
}

std::string asset(const std::string& name) {
  return std::string(GRAINSHOCK_ASSETS_DIR) + "/io/" + name;
}

// A LAMMPS dump custom with no velocities but a per-atom compute, as `dump custom ... c_pe`.
fs::path dump_without_velocities(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream f(dir / "pe.dump");
  f << "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n4\nITEM: BOX BOUNDS pp pp pp\n0 20\n0 10\n"
       "-0.5 0.5\nITEM: ATOMS id type x y z c_pe\n1 1 2 2 0 -3.5\n2 1 8 5 0 -1\n3 2 14 7 0 "
       "-2.25\n4 2 18 3 0 0.5\n";
  return dir / "pe.dump";
}

TEST(RenderFiles, AFileWithoutVelocitiesIsDrawnByAColumnOrInOneColour) {
  const fs::path dir = scratch_dir("pe");
  const fs::path dump = dump_without_velocities(dir);
  const fs::path by_pe = dir / "pe.png", plain = dir / "none.png";
  auto r =
      render(dump.string() + " --color-by c_pe --width 200 --height 100 --out " + by_pe.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = render(dump.string() + " --color-by none --width 200 --height 100 --out " + plain.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image a = read_png(by_pe.string()), b = read_png(plain.string());
  EXPECT_EQ(a.width, 200);
  EXPECT_NE(a.rgba, b.rgba) << "c_pe and one colour gave the same picture";
  // The default is the particle type (OVITO's for a file without velocities), said once with
  // what else the file can be coloured by; the same picture as --color-by type.
  const fs::path by_auto = dir / "auto.png", by_type = dir / "type.png";
  r = render(dump.string() + " --width 200 --height 100 --out " + by_auto.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("no velocities: coloured by particle type"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("type, none, id, type, c_pe"), std::string::npos) << r.err;
  r = render(dump.string() + " --color-by type --width 200 --height 100 --out " + by_type.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("coloured by particle type"), std::string::npos) << "asked: " << r.err;
  EXPECT_EQ(read_png(by_auto.string()).rgba, read_png(by_type.string()).rgba);
}

// An ASE file of three species without velocities (assets/io/species_2d.extxyz): drawn by
// species in the palette's first three colours, the note said once.
TEST(RenderFiles, SpeciesOfAnXyzFileAreItsColours) {
  const fs::path dir = scratch_dir("species");
  fs::create_directories(dir);
  const fs::path png = dir / "species.png";
  const auto r = render(asset("species_2d.extxyz") + " --dim 2 --width 400 --height 300 --out " +
                        png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t said = 0;
  for (std::size_t p = r.err.find("coloured by particle type"); p != std::string::npos;
       p = r.err.find("coloured by particle type", p + 1))
    ++said;
  EXPECT_EQ(said, 1u) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  // Discs under a pixel of radius are warned of: a one-particle change is below what shows.
  const auto tiny = render(asset("species_2d.extxyz") + " --dim 2 --framing box --width 40 --height 30 --out " +
                           (dir / "tiny.png").string());
  ASSERT_EQ(tiny.exit_code, 0) << tiny.err;
  EXPECT_NE(tiny.err.find("warning: discs of 0."), std::string::npos) << tiny.err;
  const Image img = read_png(png.string());
  for (std::size_t k = 0; k < 3; ++k) {
    const Rgb8 c = overlay_colour(k);
    std::size_t n = 0;
    for (std::size_t p = 0; p < img.rgba.size(); p += 4)
      n += img.rgba[p] == c[0] && img.rgba[p + 1] == c[1] && img.rgba[p + 2] == c[2];
    EXPECT_GT(n, 500u) << "type " << k << " (" << int(c[0]) << "," << int(c[1]) << ","
                       << int(c[2]) << ")";
  }
}

// A movie of stored dumps without velocities, coloured by their column; a frame without it is
// named before anything is made.
TEST(RenderFiles, MovieOfStoredFilesByAColumn) {
  const fs::path dir = scratch_dir("movie");
  const fs::path a = dump_without_velocities(dir / "a"), b = dump_without_velocities(dir / "b");
  const fs::path out = dir / "movie";
  auto r =
      test::grainshock("movie " + a.string() + " " + b.string() +
                       " --color-by c_pe --quiet --width 96 --height 64 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "movie.mp4"));
  std::ofstream(dir / "other.xyz")
      << "1\nLattice=\"20 0 0 0 10 0 0 0 1\" Properties=species:S:1:pos:R:3 "
         "Dim=2\nX 1 1 0\n";
  r = test::grainshock("movie " + a.string() + " " + (dir / "other.xyz").string() +
                       " --color-by c_pe --quiet --out " + (dir / "bad").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("other.xyz' has no column 'c_pe'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

// One auto colouring for a kick: a snapshot file of the active particles alone (no particle at
// rest to tell a kick by) is coloured by v/v_rms as the whole one is, so `render` of either file
// and the run's own --png frame are alike. Before the files said Initial=kick, the active file
// was drawn as raw speed (log) and was not alike.
TEST(RenderFiles, AKicksSnapshotIsColouredAlikeWithOrWithoutItsRestingParticles) {
  const fs::path all = scratch_dir("kick_all"), active = scratch_dir("kick_active");
  const std::string size = " --width 480 --height 360";
  const std::string run = "run --dim 2 --particles 3000 --t-max 300 --restitution 0.5 --png "
                          "--quiet" + size + " --out ";
  ASSERT_EQ(test::grainshock(run + all.string()).exit_code, 0);
  ASSERT_EQ(test::grainshock(run + active.string() + " --snapshot-particles active").exit_code, 0);
  const std::string snap = "/snapshots/tsim_300.xyz";
  const Snapshot moving = read_snapshot(active.string() + snap);
  ASSERT_TRUE(std::all_of(moving.active.begin(), moving.active.end(), [](auto a) { return a; }));
  EXPECT_TRUE(moving.info.kick);
  EXPECT_EQ(default_field(moving), Field::ScaledSpeed);
  std::vector<Image> drawn;
  for (const fs::path& dir : {all, active}) {
    const fs::path png = dir / "render.png";
    const auto r = render(dir.string() + snap + size + " --out " + png.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    drawn.push_back(read_png(png.string()));
  }
  const ImageComparison c = compare_images(drawn[0], drawn[1]);
  EXPECT_TRUE(c.match()) << c.differing << " px differ in " << c.blobs << " blobs";
  for (const fs::path& dir : {all, active}) {
    const fs::path frame = dir / "frames" / "tsim_300.png";
    ASSERT_TRUE(fs::exists(frame)) << frame;
    const ImageComparison f = compare_images(read_png(frame.string()), drawn[1]);
    EXPECT_TRUE(f.match()) << frame << ": " << f.differing << " px differ in " << f.blobs
                           << " blobs";
  }
}

std::size_t times_said(const std::string& err, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = err.find(what); p != std::string::npos; p = err.find(what, p + 1)) ++n;
  return n;
}

// --unwrap on a file with nothing to unwrap by (a dump of x y z, an extended XYZ file) says so,
// once; on a dump with image flags it unwraps without a word. It used to say nothing.
TEST(RenderFiles, UnwrapSaysSoOnceWhenTheFileHasNoImageFlags) {
  const fs::path dir = scratch_dir("unwrap");
  const std::string out = " --color-by none --width 200 --height 100 --out " +
                          (dir / "u.png").string();
  for (const std::string& file :
       {dump_without_velocities(dir).string(), asset("ovito_2d.xyz"),
        asset("shrinking_box_2d.lammpstrj")}) {
    const auto r = render(file + " --unwrap" + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(times_said(r.err, kNothingToUnwrap), 1u) << file << ": " << r.err;
    EXPECT_EQ(times_said(render(file + out).err, "--unwrap"), 0u) << file;
  }
  // Its first frame has image flags (its second has none, and says so).
  const auto r = render(asset("custom_3d.lammpstrj") + " --frame 0 --unwrap" + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(times_said(r.err, kNothingToUnwrap), 0u) << r.err;
}

// 300 atoms at random in a 3D box of 20 diameters, as extended XYZ without velocities.
fs::path atoms_3d(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream f(dir / "atoms.xyz");
  f << "300\nLattice=\"20 0 0 0 20 0 0 0 20\" Properties=species:S:1:pos:R:3 pbc=\"T T T\"\n";
  unsigned x = 12345;
  auto next = [&] { return (x = x * 1103515245u + 12345u) / 4294967296.0 * 20; };
  for (int i = 0; i < 300; ++i) {
    const double a = next(), b = next(), c = next();
    f << "Ar " << a << " " << b << " " << c << "\n";
  }
  return dir / "atoms.xyz";
}

// Others' 3D files are drawn whole by default, as OVITO draws them (a slab of 6 used to keep
// 117 of 300 atoms of a 20-diameter box without a word); a slab asked for says what it left out;
// a kick's snapshot keeps its slab, and says so too.
TEST(RenderFiles, A3dFileIsDrawnWholeUnlessASlabIsAskedForWhichSaysWhatItLeftOut) {
  const fs::path dir = scratch_dir("slab");
  const fs::path atoms = atoms_3d(dir);
  const std::string out = " --width 200 --height 150 --out " + (dir / "a.png").string();
  auto r = render(atoms.string() + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(times_said(r.err, "the slab"), 0u) << r.err;
  ASSERT_EQ(render(atoms.string() + " --slab 0 --width 200 --height 150 --out " +
                   (dir / "whole.png").string())
                .exit_code,
            0);
  EXPECT_EQ(read_png((dir / "a.png").string()).rgba, read_png((dir / "whole.png").string()).rgba)
      << "the default is not the whole box";
  r = render(atoms.string() + " --slab 6" + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t at = r.err.find("the slab 6 thick through the centre kept ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const long kept = std::stol(r.err.substr(at + 41));
  EXPECT_GT(kept, 50);  // a slab of 6 of a box of 20: about 3/10 of them
  EXPECT_LT(kept, 200);
  EXPECT_NE(r.err.find(" of 300 particles (--slab 0 draws all)"), std::string::npos) << r.err;
  EXPECT_EQ(times_said(r.err, "the slab"), 1u) << r.err;

  const fs::path kick = scratch_dir("slab_kick");
  ASSERT_EQ(test::grainshock("run --dim 3 --particles 3000 --t-max 100 --quiet --out " +
                             kick.string())
                .exit_code,
            0);
  r = render((kick / "snapshots" / "tsim_100.xyz").string() + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("the slab 6 thick through the centre kept "), std::string::npos) << r.err;
}

// Each bad file: exit 1, one line that names the file and where, and no PNG.
void expect_refused(const fs::path& file, const std::string& extra, const std::string& where) {
  const fs::path png = file.string() + ".png";
  const CommandResult r = render(file.string() + extra + " --out " + png.string());
  EXPECT_EQ(r.exit_code, 1) << file << ": " << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find(file.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(where), std::string::npos) << "expected '" << where << "' in " << r.err;
  EXPECT_FALSE(fs::exists(png));
}

fs::path write(const fs::path& dir, const std::string& name, const std::string& bytes) {
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}

TEST(RenderFiles, BadFilesAreNamedWithTheLineOrFrame) {
  const fs::path dir = scratch_dir("bad");
  fs::create_directories(dir);
  const std::string xyz = "2\nProperties=species:S:1:pos:R:3:velo:R:3\n";
  expect_refused(write(dir, "truncated.xyz", xyz + "X 0 0 0 1 0 0\n"), "", "truncated");
  expect_refused(write(dir, "second_truncated.xyz",
                       xyz + "X 0 0 0 1 0 0\nX 1 1 1 0 0 0\n" + xyz + "X 0 0 0 1 0 0\n"),
                 " --frame 1", "frame 1");
  std::string many;
  for (int i = 0; i < 5; ++i) many += "X 0 0 0 1 0 0\n";
  expect_refused(write(dir, "count.xyz", xyz + many), "", "line 5");
  expect_refused(write(dir, "nan.xyz", xyz + "X 0 0 0 1 0 0\nX 1 nan 1 0 0 0\n"), "", "line 4");
  expect_refused(write(dir, "inf.xyz", xyz + "X 0 0 0 1 0 0\nX 1 1 -inf 0 0 0\n"), "", "line 4");
  expect_refused(asset("ovito_2d.xyz"), " --frame 1", "1 frame");

  const std::string box = "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n";
  const std::string atoms = "ITEM: ATOMS id x y z vx vy vz\n1 0 0 0 1 0 0\n2 .5 .5 .5 0 0 0\n";
  expect_refused(write(dir, "no_number.dump", "ITEM: TIMESTEP\n0\n" + box + atoms), "",
                 "NUMBER OF ATOMS");
  expect_refused(write(dir, "no_box.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\n" + atoms),
                 "", "BOX BOUNDS");
  expect_refused(asset("custom_3d.lammpstrj"), " --frame 99", "frame");

  const fs::path good = dir / "good.gsd";
  Snapshot s;
  s.info.dim = 2;
  s.info.set_cubic_box(10);
  s.position = {{1, 1, 0}, {3, 4, 0}};
  s.velocity = {{1, 0, 0}, {0, 0, 0}};
  s.radius = {0.5, 0.5};
  s.active = {1, 0};
  write_gsd(good.string(), s);
  ASSERT_EQ(render(good.string() + " --out " + (dir / "good.png").string()).exit_code, 0);
  const std::string bytes = test::read_file(good);
  std::string bad_magic = bytes;
  bad_magic[0] ^= 0x40;
  expect_refused(write(dir, "magic.gsd", bad_magic), "", "magic");
  std::string bad_index = bytes;
  const std::uint64_t far = 1ull << 50;
  std::memcpy(bad_index.data() + 8, &far, 8);  // the index location
  expect_refused(write(dir, "index.gsd", bad_index), "", "index");
  expect_refused(good, " --frame 1", "1 frame");
}

// One default frame for `render` and Python's grainshock.read: the last of a multi-frame file.
TEST(RenderFiles, TheDefaultFrameIsTheLast) {
  const fs::path dir = scratch_dir("default_frame");
  fs::create_directories(dir);
  const std::string file = asset("hoomd_2d_2frames.gsd") + " --color-by speed --no-time";
  std::vector<std::vector<std::uint8_t>> pictures;
  for (const char* frame : {"", " --frame -1", " --frame 0"}) {
    const fs::path png = dir / "f.png";
    const auto r = render(file + frame + " --width 200 --height 150 --out " + png.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    pictures.push_back(read_png(png.string()).rgba);
    fs::remove(png);
  }
  EXPECT_EQ(pictures[0], pictures[1]) << "the default is not the last frame";
  EXPECT_NE(pictures[0], pictures[2]) << "the two frames drew alike: the test cannot tell";
}

}  // namespace
}  // namespace gs::render
