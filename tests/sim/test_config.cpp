#include <gtest/gtest.h>

#include <cmath>

#include "sim/config.h"
#include "sim/error.h"

namespace gs {
namespace {

TEST(Config, ElasticIsRestitutionOne) {
  PhysicsConfig c;
  c.restitution = 1.0;
  EXPECT_TRUE(c.elastic());
  for (const double r : {0.0, 0.1, 0.95, std::nextafter(1.0, 0.0)}) {
    c.restitution = r;
    EXPECT_FALSE(c.elastic()) << r;
  }
}

// GS_DCHECK is GS_CHECK in Debug builds and nothing (not even evaluated) in Release ones.
TEST(Config, DebugOnlyChecksCostNothingInRelease) {
  int evaluated = 0;
  GS_DCHECK(++evaluated > 0);
#ifdef NDEBUG
  EXPECT_EQ(evaluated, 0);
  GS_DCHECK(false);  // would abort in a Debug build
#else
  EXPECT_EQ(evaluated, 1);
  EXPECT_DEATH(GS_DCHECK(evaluated == 0), "evaluated == 0");
#endif
}

TEST(Config, BoxSideFollowsDensity) {
  PhysicsConfig c;
  c.dim = 2;
  c.particles = 250000;
  c.density = 0.25;
  EXPECT_NEAR(c.box(), 1000.0, 1e-9);  // the paper's 2D box: (2.5e5 / 0.25)^(1/2)
  c.dim = 3;
  c.particles = 2000000;
  EXPECT_NEAR(c.box(), 200.0, 1e-9);  // the paper's 3D box
  EXPECT_NEAR(c.paper_time(10.0), 10.0 * std::cbrt(0.25), 1e-12);
}

// Kicks in 2D and 3D default to the unbounded medium; thermal gases, 1D and lattices keep the box.
TEST(Config, DefaultMediumIsUnboundedForKicksIn2DAnd3D) {
  PhysicsConfig c;
  EXPECT_EQ(default_medium(c), Medium::Unbounded);
  c.dim = 3;
  EXPECT_EQ(default_medium(c), Medium::Unbounded);
  c.initial = Initial::Thermal;
  EXPECT_EQ(default_medium(c), Medium::Box);
  c = PhysicsConfig{};
  c.dim = 1;
  EXPECT_EQ(default_medium(c), Medium::Box);
  c.lattice = 2;
  EXPECT_EQ(default_medium(c), Medium::Box);
  // The struct itself stays the paper's box, and files state the box that to_toml leaves out.
  EXPECT_EQ(PhysicsConfig{}.medium, Medium::Box);
  EXPECT_EQ(to_toml(PhysicsConfig{}).find("medium"), std::string::npos);
  EXPECT_EQ(physics_toml(PhysicsConfig{}), to_toml(PhysicsConfig{}) + "medium = \"box\"\n");
}

TEST(Config, RejectsImpossibleInputNamingTheFlag) {
  auto message = [](auto mutate) {
    PhysicsConfig c;
    mutate(c);
    try {
      validate(c);
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message([](PhysicsConfig& c) { c.dim = 4; }).find("--dim"), std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.particles = 1; }).find("--particles"),
            std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.density = 0; }).find("--density"), std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.density = 0.8; }).find("--density"),
            std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.restitution = 1.5; }).find("--restitution"),
            std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.restitution = -0.1; }).find("--restitution"),
            std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.cutoff = -1; }).find("--cutoff"), std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.t_max = 0; }).find("--t-max"), std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) { c.lattice = 2; }).find("--lattice"), std::string::npos);
  EXPECT_NE(message([](PhysicsConfig& c) {
              c.dim = 2;
              c.particles = 200000000;
              c.density = 0.1;  // box side 44721
            }).find("--density"),
            std::string::npos);
  EXPECT_EQ(message([](PhysicsConfig&) {}), "accepted");
  EXPECT_EQ(message([](PhysicsConfig& c) { c.restitution = 1.0; }), "accepted");
  EXPECT_EQ(message([](PhysicsConfig& c) { c.restitution = 0.0; }), "accepted");
}

}  // namespace
}  // namespace gs
