// RunLoop::resume and the medium's default: run.toml states the box since kicks default to the
// unbounded medium, and a box run's checkpoint written before (whose lines do not) still resumes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "jobs/run_loop.h"
#include "sim/config.h"
#include "sim/error.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

TEST(RunLoopResume, ABoxCheckpointFromBeforeTheMediumDefaultResumes) {
  RunPlan plan;
  plan.physics.particles = 2000;
  plan.physics.restitution = 0.5;
  plan.physics.t_max = 50;
  const fs::path dir =
      fs::temp_directory_path() / ("gs_run_loop_resume_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string now = "# run\n" + physics_toml(plan.physics);
  const std::string before = "# run\n" + to_toml(plan.physics);
  ASSERT_NE(now, before);
  { RunLoop first(plan, dir, before); }  // writes its first checkpoint
  auto loop = RunLoop::resume(plan, dir, now);
  EXPECT_TRUE(loop->run());
  // Any other difference is still refused.
  PhysicsConfig other = plan.physics;
  other.seed = 2;
  EXPECT_THROW(RunLoop::resume(plan, dir, "# run\n" + physics_toml(other)), UserError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs::jobs
