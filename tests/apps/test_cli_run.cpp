#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "analysis/json.h"
#include "analysis/table.h"
#include "io/snapshot_file.h"
#include "io/snapshot_writer.h"
#include "render/png.h"
#include "tests/apps/cli_test_util.h"

namespace gs {
namespace {

using test::grainshock;
using test::read_file;
using test::scratch_dir;
namespace fs = std::filesystem;

// A box of 3000 discs: these tests read the box's N back (summary.json, snapshots).
const std::string kSmall = "--medium box --particles 3000 --t-max 300 --restitution 0.5 --quiet";

TEST(CliRun, WritesTheRunFolder) {
  const auto dir = scratch_dir("run");
  const auto r = grainshock("run " + kSmall + " --snapshot-times 100,200 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"run.toml", "timeseries.csv", "summary.json", "snapshots/tsim_100.xyz",
                        "snapshots/tsim_200.xyz", "snapshots/tsim_300.xyz"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const std::string csv = read_file(dir / "timeseries.csv");
  EXPECT_EQ(
      csv.substr(0, csv.find('\n')),
      "t,t_paper,active,energy,radius_rms,speed_rms,anisotropy,collisions,events,overlaps,px,py");
  const std::string summary = read_file(dir / "summary.json");
  // summary.json holds the run's last sample, to the bit: the last row of timeseries.csv (whose
  // numbers are exact too, tests/analysis/test_table.cpp).
  const Json j = Json::parse(summary);
  const Table ts = read_csv(dir / "timeseries.csv");
  const std::size_t last = ts.rows() - 1;
  EXPECT_EQ(j.at("t_end").get<double>(), 300.0);
  EXPECT_EQ(j.at("t_end").get<double>(), ts.column("t")[last]);
  EXPECT_EQ(j.at("energy").get<double>(), ts.column("energy")[last]);
  EXPECT_EQ(j.at("radius_rms").get<double>(), ts.column("radius_rms")[last]);
  EXPECT_EQ(j.at("active").get<double>(), ts.column("active")[last]);
  EXPECT_EQ(j.at("collisions").get<double>(), ts.column("collisions")[last]);
  EXPECT_EQ(j.at("interrupted"), false);
  EXPECT_EQ(j.at("particles"), 3000);
  // Wall times are apart, so that summary.json is the same on every run of the same job.
  EXPECT_EQ(summary.find("seconds"), std::string::npos);
  const std::string timing = read_file(dir / "timing.json");
  for (const char* key :
       {"\"setup_seconds\"", "\"run_seconds\"", "\"snapshot_seconds\"", "\"checkpoint_seconds\""})
    EXPECT_NE(timing.find(key), std::string::npos) << key;
  const Snapshot s = read_snapshot((dir / "snapshots/tsim_300.xyz").string());
  EXPECT_EQ(s.size(), 3000u);
  EXPECT_EQ(s.info.dim, 2);
  EXPECT_DOUBLE_EQ(s.info.time, 300.0);
}

// The unbounded medium: the snapshots hold the particles made (fewer than --particles allows),
// the pictures frame the active ones, and a run that needs more particles stops naming the flag.
TEST(CliRun, UnboundedMediumRun) {
  const auto dir = scratch_dir("unbounded");
  const std::string args =
      "run --medium unbounded --particles 20000 --t-max 300 "
      "--restitution 0.5 --quiet --png --width 320 --height 320 --out ";
  auto r = grainshock(args + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Snapshot s = read_snapshot((dir / "snapshots/tsim_300.xyz").string());
  const Table ts = read_csv(dir / "timeseries.csv");
  const double active = ts.column("active")[ts.rows() - 1];
  EXPECT_GT(active, 50);
  EXPECT_GT(s.size(), static_cast<std::size_t>(active));
  EXPECT_LT(s.size(), 20000u);
  // summary.json says how many the medium made: the snapshot's particles.
  EXPECT_EQ(Json::parse(read_file(dir / "summary.json")).at("particles_made").get<std::size_t>(),
            s.size());
  EXPECT_TRUE(fs::exists(dir / "frames/tsim_300.png"));
  EXPECT_NE(read_file(dir / "run.toml").find("medium = \"unbounded\""), std::string::npos);
  // "The whole box" is the addressable region: refused in one line; the default frames the band.
  const std::string snap = (dir / "snapshots/tsim_300.xyz").string();
  EXPECT_TRUE(s.info.unbounded);
  r = grainshock("render " + snap + " --framing box --out " + (dir / "box.png").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--framing box: " + snap + " is of the unbounded medium"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "box.png"));
  EXPECT_EQ(grainshock("render " + snap + " --out " + (dir / "fit.png").string()).exit_code, 0);
  // A kick names no medium: unbounded, the same bytes; a thermal start keeps the box.
  const auto implicit = scratch_dir("unbounded_by_default");
  ASSERT_EQ(grainshock("run --particles 20000 --t-max 300 --restitution 0.5 --quiet --out " +
                       implicit.string())
                .exit_code,
            0);
  EXPECT_EQ(read_file(implicit / "timeseries.csv"), read_file(dir / "timeseries.csv"));
  EXPECT_NE(read_file(implicit / "run.toml").find("medium = \"unbounded\""), std::string::npos);
  const auto thermal = scratch_dir("thermal_box");
  ASSERT_EQ(grainshock("run --initial thermal --particles 400 --t-max 1 --quiet --out " +
                       thermal.string())
                .exit_code,
            0);
  EXPECT_NE(read_file(thermal / "run.toml").find("medium = \"box\""), std::string::npos);
  r = grainshock("run --medium unbounded --particles 500 --t-max 3000 --quiet --out " +
                 scratch_dir("unbounded_full").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("--particles 500"), std::string::npos) << r.err;
}

TEST(CliRun, PicturesOfSnapshotsOverlayAndElasticComparison) {
  const auto dir = scratch_dir("png");
  const auto r = grainshock("run " + kSmall +
                            " --snapshot-times 100,200 --png --compare-elastic --width 640 "
                            "--height 360 --out " +
                            dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f :
       {"frames/tsim_100.png", "frames/tsim_200.png", "frames/tsim_300.png", "frames/overlay.png",
        "frames/elastic_tsim_150.png", "snapshots/elastic_tsim_150.xyz"}) {
    ASSERT_TRUE(fs::exists(dir / f)) << f;
    if (fs::path(f).extension() != ".png") continue;
    const render::Image img = render::read_png((dir / f).string());
    EXPECT_EQ(img.width, 640) << f;
    EXPECT_EQ(img.height, 360) << f;
  }
  // The elastic gas moves the same kick's energy without loss.
  const Snapshot elastic = read_snapshot((dir / "snapshots/elastic_tsim_150.xyz").string());
  double energy = 0;
  for (const auto& v : elastic.velocity) energy += 0.5 * v.squaredNorm();
  EXPECT_NEAR(energy, 0.5, 1e-12);
  EXPECT_EQ(elastic.info.restitution.value_or(-1), 1.0);
}

// The elastic comparison fails on its own account, and says so: its front outruns the inelastic
// one, so 2000 particles of the unbounded medium last the run at r = 0.05 to t = 3000 (about
// 11000) but not the elastic one to t = 1500 (about 510); it was reported as the run's failure.
TEST(CliRun, TheElasticComparisonNamesItsOwnFailure) {
  const auto dir = scratch_dir("elastic_short");
  const std::string physics = "--dim 2 --particles 2000 --restitution 0.05 --t-max 3000 --quiet";
  const auto alone = grainshock("run " + physics + " --out " + (dir / "alone").string());
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  const auto r = grainshock("run " + physics + " --compare-elastic --width 64 --height 48 --out " +
                            (dir / "both").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("the elastic comparison of --compare-elastic (r = 1, to t = 1500): "
                       "--particles 2000: the unbounded medium has made as many particles"),
            std::string::npos)
      << r.err;
}

// README's first command: `grainshock run` with nothing but where to write runs the paper's
// Fig. 1 job (2.5e5 discs, r = 0.1; tens of seconds).
TEST(CliRun, NoPhysicsFlagsRunTheFig1Job) {
  const auto dir = scratch_dir("fig1");
  const auto r = grainshock("run --quiet --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Paper times 5000, 10000, 20000, 50000 are simulation times 10000 ... 100000 at n = 0.25.
  for (const char* f :
       {"frames/tsim_10000.png", "frames/tsim_20000.png", "frames/tsim_40000.png",
        "frames/tsim_100000.png", "frames/overlay.png", "frames/elastic_tsim_50000.png",
        "snapshots/tsim_100000.xyz", "movie.mp4", "timeseries.csv"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  // The paper's box, stated in run.toml so that --config gives it again.
  EXPECT_NE(read_file(dir / "run.toml").find("medium = \"box\""), std::string::npos);
  const Snapshot s = read_snapshot((dir / "snapshots/tsim_100000.xyz").string());
  EXPECT_EQ(s.size(), 250000u);
  EXPECT_EQ(s.info.restitution.value_or(-1), 0.1);
  EXPECT_EQ(render::read_png((dir / "frames/overlay.png").string()).width, 1920);
}

TEST(CliRun, SameConfigAndSeedGiveIdenticalBytes) {
  const auto a = scratch_dir("a"), b = scratch_dir("b"), c = scratch_dir("c");
  ASSERT_EQ(grainshock("run " + kSmall + " --seed 7 --out " + a.string()).exit_code, 0);
  ASSERT_EQ(grainshock("run " + kSmall + " --seed 7 --out " + b.string()).exit_code, 0);
  EXPECT_EQ(read_file(a / "timeseries.csv"), read_file(b / "timeseries.csv"));
  // The written run.toml reproduces the run on its own.
  ASSERT_EQ(grainshock("run --quiet --config " + (a / "run.toml").string() + " --out " + c.string())
                .exit_code,
            0);
  EXPECT_EQ(read_file(a / "timeseries.csv"), read_file(c / "timeseries.csv"));
  const auto d = scratch_dir("d");
  ASSERT_EQ(grainshock("run " + kSmall + " --seed 8 --out " + d.string()).exit_code, 0);
  EXPECT_NE(read_file(a / "timeseries.csv"), read_file(d / "timeseries.csv"));
}

// --snapshot-particles active takes the moving particles from the engine alone (no copy of every
// particle first): the very particles and numbers that filtering the whole snapshot gives, in 2D
// and 3D, and at a time with particles at rest around the band.
TEST(CliRun, ActiveSnapshotsAreTheActiveParticlesOfTheWholeOnes) {
  for (const std::string dim : {"2", "3"}) {
    const auto all = scratch_dir("all" + dim), active = scratch_dir("active" + dim);
    const std::string c = "--dim " + dim + " " + kSmall + " --snapshot-times 30";
    ASSERT_EQ(grainshock("run " + c + " --out " + all.string()).exit_code, 0);
    ASSERT_EQ(
        grainshock("run " + c + " --snapshot-particles active --out " + active.string()).exit_code,
        0);
    for (const char* name : {"snapshots/tsim_30.xyz", "snapshots/tsim_300.xyz"}) {
      const Snapshot whole = read_snapshot((all / name).string());
      const Snapshot moving = read_snapshot((active / name).string());
      Snapshot expected;
      active_particles(whole, expected);
      ASSERT_GT(expected.size(), 0u) << name;
      ASSERT_LT(expected.size(), whole.size()) << name << ": none at rest";
      ASSERT_EQ(moving.size(), expected.size()) << name;
      EXPECT_TRUE(moving.position == expected.position) << name;
      EXPECT_TRUE(moving.velocity == expected.velocity) << name;
      EXPECT_TRUE(moving.first_collision == expected.first_collision) << name;
    }
  }
}

TEST(CliRun, ThermalRunsReportPressure) {
  const auto dir = scratch_dir("thermal");
  ASSERT_EQ(grainshock("run --initial thermal --dim 3 --particles 2000 --t-max 5 --restitution 1 "
                       "--quiet --out " +
                       dir.string())
                .exit_code,
            0);
  const std::string csv = read_file(dir / "timeseries.csv");
  EXPECT_NE(csv.substr(0, csv.find('\n')).find("pz,pressure,collision_rate"), std::string::npos);
}

// Bad input: one line on stderr naming the problem, a non-zero exit, and an existing folder
// with earlier results left exactly as it was.
TEST(CliRun, BadInputIsOneLineAndTouchesNothing) {
  const auto dir = scratch_dir("earlier");
  fs::create_directories(dir);
  { std::ofstream(dir / "timeseries.csv") << "earlier results\n"; }
  const std::string out = " --out " + dir.string();
  const std::pair<std::string, std::string> cases[] = {
      {"run --bogus", "--bogus"},
      {"run --dim 4", "--dim"},
      {"run --particles 1", "--particles"},
      {"run --density 0", "--density"},
      {"run --density 0.9", "--density"},
      {"run --dim 3 --density 0.8", "--density"},
      {"run --restitution 1.2", "--restitution"},
      {"run --restitution -0.5", "--restitution"},
      {"run --cutoff -1", "--cutoff"},
      {"run --t-max 0", "--t-max"},
      {"run --t-max -3", "--t-max"},
      {"run --initial warm", "--initial"},
      {"run --lattice 0.5 --dim 1", "--lattice"},
      {"run --particles 100 --t-max 1", "not empty"},
      {"run --png --width 0", "image size 0x1080"},
      {"run --snapshot-times 5,1e9", "--snapshot-times"},
      // Sizes are checked against memory and the cell-grid limits before anything is made.
      {"run --dim 3 --particles 1000000000000", "GB of memory"},
      // Counts in scientific notation are read as the whole numbers they are, or named.
      {"run --dim 3 --particles 1e12", "GB of memory"},
      {"run --dim 3 --medium box --particles 1e9", "needs about 268 GB of memory"},
      {"run --particles 2.5e0", "not a whole number"},
      {"run --sample-every 1e-7", "use --sample-every 0.01 or more"},
      {"run --particles 2000 --density 2e-6", "neighbour cells"},
      {"run --dim 1 --particles 1000 --density 1e-7", "use --density"},
      {"run --dim 1 --particles 1000 --lattice 1e9", "use --lattice"},
      {"run --seed -1", "--seed"},
      {"run --cutoff inf", "--cutoff"},
      {"run --lattice inf --dim 1", "--lattice"},
      {"run --snapshot-format pdb", "--snapshot-format"},
      {"run --snapshot-particles moving", "--snapshot-particles"},
      {"run --dim 1 --particles 100 --snapshot-format gsd", "use xyz in 1D"},
      {"run --medium open", "--medium"},
      {"run --medium unbounded --dim 1", "--medium"},
      {"run --medium unbounded --initial thermal", "--medium"},
      {"run --medium unbounded --density 0.6", "--density"},
      {"movie --medium unbounded --camera fixed", "--camera"},
  };
  for (const auto& [args, names] : cases) {
    const auto r = grainshock(args + out);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(names), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(read_file(dir / "timeseries.csv"), "earlier results\n") << args;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << args;
  }
  const auto cfg = scratch_dir("bad.toml");
  { std::ofstream(cfg) << "dim = \n"; }
  auto r = grainshock("run --config " + cfg.string() + out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("malformed"), std::string::npos) << r.err;
  { std::ofstream(cfg) << "dimension = 3\n"; }
  r = grainshock("run --config " + cfg.string() + out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("unknown key 'dimension'"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir / "timeseries.csv"), "earlier results\n");
}

TEST(CliRun, HelpOnEveryLevel) {
  EXPECT_EQ(grainshock("--help").exit_code, 0);
  EXPECT_EQ(grainshock("run --help").exit_code, 0);
}

}  // namespace
}  // namespace gs
