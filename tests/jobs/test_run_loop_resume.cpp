// Resuming a run and the medium's default: run.toml states the box since kicks default to the
// unbounded medium, while a run's checkpoints know it by run_spec(), which leaves the box
// unstated as every checkpoint written before did; so a box run checkpointed then resumes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "jobs/run_job.h"
#include "jobs/run_loop.h"
#include "sim/config.h"
#include "sim/error.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

TEST(RunLoopResume, ABoxCheckpointFromBeforeTheMediumDefaultResumes) {
  RunOptions o;
  o.plan.physics.particles = 2000;
  o.plan.physics.restitution = 0.5;
  o.plan.physics.t_max = 50;
  o.quiet = true;
  const fs::path dir =
      fs::temp_directory_path() / ("gs_run_loop_resume_" + std::to_string(::getpid()));
  o.out = dir.string();
  fs::remove_all(dir);
  fs::create_directories(dir);
  // The run.toml of a box run before the default had no medium key, and its checkpoints the same
  // lines; today's run.toml states the box.
  std::string before = run_toml(o);
  const std::string box_line = "medium = \"box\"\n";
  ASSERT_NE(before.find(box_line), std::string::npos);
  before.erase(before.find(box_line), box_line.size());
  { RunLoop first(o.plan, dir, before); }  // writes its first checkpoint
  EXPECT_FALSE(run_job(o, true).stopped);
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
  // Any other difference is still refused.
  fs::remove_all(dir);
  fs::create_directories(dir);
  { RunLoop first(o.plan, dir, before); }
  o.plan.physics.seed = 2;
  EXPECT_THROW(run_job(o, true), UserError);
  fs::remove_all(dir);
}

// A job writes nothing to the terminal: its notes go to the sink it is given (the command line's
// prints them, Python's warns), and a job given none says nothing.
TEST(RunJob, NotesGoToTheSinkNotToStderr) {
  RunOptions o;
  o.plan.physics.dim = 1;
  o.plan.physics.particles = 200;
  o.plan.physics.t_max = 50;
  const fs::path dir =
      fs::temp_directory_path() / ("gs_run_job_notes_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  o.out = dir.string();
  std::vector<std::string> notes;
  o.messages = [&](MessageKind kind, const std::string& text) {
    EXPECT_EQ(kind, MessageKind::Note);
    notes.push_back(text);
  };
  testing::internal::CaptureStderr();
  EXPECT_FALSE(run_job(o, false).stopped);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0].rfind("finished kick: ", 0), 0u) << notes[0];
  EXPECT_NE(notes[0].find("results in " + dir.string()), std::string::npos) << notes[0];
  // Without a sink, nothing is said.
  o.messages = {};
  o.force = true;
  testing::internal::CaptureStderr();
  EXPECT_FALSE(run_job(o, false).stopped);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs::jobs
