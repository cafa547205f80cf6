// Checkpoints: an engine loaded from one continues the very same history, event for event and
// bit for bit, ties included; damaged or foreign checkpoint files are refused in one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/append_file.h"
#include "io/checkpoint.h"
#include "io/simulation_file.h"
#include "sim/engine.h"
#include "sim/error.h"
#include "sim/initial.h"
#include "tests/sim/same_history.h"

namespace gs {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "checkpoint" / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir / name;
}

void save(const Simulation& sim, const fs::path& file) {
  CheckpointWriter out(file, file.string() + ".prev",
                       {sim.dim(), static_cast<std::uint64_t>(sim.config().particles)});
  sim.save(out);
  out.commit();
}

std::unique_ptr<Simulation> load(const PhysicsConfig& c, const fs::path& file) {
  CheckpointReader in(file);
  auto sim = load_simulation(c, in);
  in.finish();
  return sim;
}

using test::expect_same_history;

// Saved after the resting store's first compaction (at 1024 dead slots, Engine::kCompactAt): the
// checkpoint holds the compacted store and the predictions' renamed slots.
TEST(Checkpoint, KickContinuesTheSameHistory2DAnd3D) {
  for (int dim : {2, 3}) {
    PhysicsConfig c;
    c.dim = dim;
    c.particles = 20000;
    c.restitution = 0.8;
    auto a = make_simulation(c);
    a->run_until(dim == 2 ? 2500 : 400);
    ASSERT_GT(a->sample().active, 1100) << "saved after a compaction";
    const fs::path file = scratch("kick" + std::to_string(dim) + ".bin");
    save(*a, file);
    auto b = load(c, file);
    expect_same_history(*a, *b, 200000);
    EXPECT_GT(a->stats().collisions, 10000) << "the comparison saw a real history";
  }
}

// The unbounded medium's checkpoint holds the cells made so far (a short list, not the
// addressable grid); the loaded engine makes the same cells at the same events.
TEST(Checkpoint, UnboundedMediumContinuesTheSameHistory) {
  for (int dim : {2, 3}) {
    PhysicsConfig c;
    c.dim = dim;
    c.medium = Medium::Unbounded;
    c.particles = 100000;
    c.restitution = 0.5;
    auto a = make_simulation(c);
    a->run_until(300);
    const fs::path file = scratch("unbounded" + std::to_string(dim) + ".bin");
    save(*a, file);
    EXPECT_LT(fs::file_size(file), 200 * a->snapshot().size() + 4096) << "a sparse checkpoint";
    auto b = load(c, file);
    const std::size_t made = a->snapshot().size();
    expect_same_history(*a, *b, 200000);
    EXPECT_GT(a->stats().collisions, 10000) << "the comparison saw a real history";
    EXPECT_GT(a->snapshot().size(), made) << "and cells made after the load";
  }
}

TEST(Checkpoint, ThermalAnd1DStickyContinueTheSameHistory) {
  PhysicsConfig thermal;
  thermal.dim = 3;
  thermal.particles = 2000;
  thermal.restitution = 0.9;
  thermal.initial = Initial::Thermal;
  PhysicsConfig sticky;
  sticky.dim = 1;
  sticky.particles = 2000;
  sticky.restitution = 0;
  sticky.lattice = 2;
  for (const PhysicsConfig& c : {thermal, sticky}) {
    auto a = make_simulation(c);
    a->run_until(c.dim == 1 ? 500 : 0.5);
    const fs::path file = scratch("state.bin");
    save(*a, file);
    auto b = load(c, file);
    expect_same_history(*a, *b, 100000);
  }
}

// Columns of a square lattice moving in alternate directions: every pair of columns meets at
// the same instant, so the queue and the searches break thousands of exact ties. A loaded
// engine must break them the same way (it holds the queue's and the cells' lists in order).
TEST(Checkpoint, TiesAreBrokenTheSameWay) {
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 40 * 40;
  c.density = 0.2;
  c.restitution = 0.8;
  c.initial = Initial::Thermal;
  InitialState<2> init;
  Rng lattice_rng(1, 0, Stream::Positions);  // 40^2 sites, none left empty: unused
  init.position = cubic_lattice<2>(c.particles, c.box(), lattice_rng);
  init.velocity.resize(init.position.size());
  for (std::size_t i = 0; i < init.position.size(); ++i)
    init.velocity[i] = Vec<2>((i % 40) % 2 ? -1.0 : 1.0, 0.0);
  Engine<2> a(c, std::move(init));
  for (int k = 0; k < 3000; ++k) a.step();
  const fs::path file = scratch("ties.bin");
  save(a, file);
  auto b = load(c, file);
  expect_same_history(a, *b, 20000);
}

std::string bytes_of(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void put(const fs::path& f, const std::string& bytes) {
  std::ofstream(f, std::ios::binary | std::ios::trunc) << bytes;
}

std::string refusal(const PhysicsConfig& c, const fs::path& f) {
  try {
    load(c, f);
  } catch (const UserError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Checkpoint, DamagedOrForeignFilesAreRefusedInOneLine) {
  PhysicsConfig c;
  c.particles = 2000;
  auto sim = make_simulation(c);
  sim->run_until(50);
  const fs::path file = scratch("good.bin"), bad = file.parent_path() / "bad.bin";
  save(*sim, file);
  const std::string good = bytes_of(file);
  // Offsets in the fixed header: magic 0, format 8, version 24, instruction set 56.
  struct Case {
    const char* name;
    std::string bytes;
    const char* says;
  };
  std::string corrupt = good, format = good, version = good, isa = good, magic = good;
  corrupt[good.size() / 2] ^= 0x10;
  format[8] = 99;
  version[24] = '9';
  std::memcpy(&isa[56], "riscv", 5);
  magic[0] = 'X';
  const Case cases[] = {
      {"truncated", good.substr(0, good.size() - 100), "truncated"},
      {"a header only", good.substr(0, 40), "truncated"},
      {"one flipped bit", corrupt, "checksum"},
      {"another format", format, "format 99"},
      {"another version", version, "written by grainshock 9"},
      {"another instruction set", isa, "written by a build for riscv"},
      {"not a checkpoint", magic, "not a grainshock checkpoint"},
  };
  for (const Case& k : cases) {
    put(bad, k.bytes);
    const std::string why = refusal(c, bad);
    EXPECT_NE(why.find(k.says), std::string::npos) << k.name << ": " << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << k.name;
  }
  PhysicsConfig other = c;
  other.restitution = 0.5;
  EXPECT_NE(refusal(other, file).find("other physics"), std::string::npos);
  EXPECT_EQ(refusal(c, file), "(accepted)");
}

// A saved Simulation stores its PhysicsConfig as bytes; one saved before `medium` was added has
// the old tag and a shorter config, and is named as such rather than read with shifted fields.
TEST(SimulationFile, ALayoutBeforeTheMediumIsNamedAndTheCurrentOneLoads) {
  PhysicsConfig c;
  c.particles = 2000;
  auto sim = make_simulation(c);
  sim->run_until(50);
  const fs::path file = scratch("sim.bin"), old = file.parent_path() / "old.bin";
  save_simulation(*sim, file);
  EXPECT_EQ(load_simulation_file(file)->time(), 50.0);
  {
    CheckpointWriter out(old, old.string() + ".prev", {c.dim, 2000});
    out.string("grainshock simulation");
    out.value(c);
    sim->save(out);
    out.commit();
  }
  try {
    load_simulation_file(old);
    ADD_FAILURE() << "a file of the old layout was loaded";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("older grainshock"), std::string::npos) << e.what();
  }
}

// A full disk: the write fails naming the OS reason, and what the file holds ends on a record.
TEST(AppendFile, FailedWritesNameTheReason) {
  AppendFile full("/dev/full", 0);
  try {
    full.append("t,energy\n");
    FAIL() << "a write to /dev/full succeeded";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
  EXPECT_EQ(full.size(), 0u);
  const fs::path file = scratch("rows.csv");
  {
    AppendFile f(file, 0);
    f.append("a\n");
    f.append("b\n");
  }
  AppendFile again(file, 2);  // a resumed run keeps the rows of its checkpoint
  again.append("c\n");
  EXPECT_EQ(bytes_of(file), "a\nc\n");
  EXPECT_THROW(AppendFile(file, 100), UserError);
}

}  // namespace
}  // namespace gs
