// A figures job stopped part-way and resumed writes what a job never stopped writes (the
// --limit runs last days: a kill must not lose them), and the folder's refusals.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "analysis/json.h"
#include "jobs/figures_job.h"
#include "sim/error.h"
#include "sim/stop.h"

namespace gs::jobs {
namespace {

namespace fs = std::filesystem;

std::string text_of(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Asks the job to stop (as SIGINT does) at the `n`-th progress update: after n realisations.
class StopAt : public ProgressLine {
 public:
  explicit StopAt(int n) : left_(n) {}
  void update(double, const std::string&) override {
    if (--left_ == 0) request_stop();
  }
  void done() override {}

 private:
  int left_;
};

FiguresOptions tiny(const fs::path& dir) {
  FiguresOptions o;
  o.mode = FiguresMode::Tiny;
  o.threads = 2;
  o.quiet = true;
  o.out = dir.string();
  o.settings = "tiny = true\n";
  return o;
}

// The results of a figures folder: every ensemble's averages and the comparisons (not the walls).
std::string results_of(const fs::path& dir) {
  std::string all;
  for (const auto& e : fs::directory_iterator(dir / "ensembles"))
    for (const char* f : {"timeseries_mean.csv", "distributions_mean.csv"})
      all += e.path().filename().string() + "/" + f + "\n" + text_of(e.path() / f);
  const Json j = Json::parse(text_of(dir / "summary.json"));
  return all + j.at("comparisons").dump();
}

class FiguresResume : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override {
    clear_stop();
    fs::remove_all(root_);
  }
  const fs::path root_ =
      fs::temp_directory_path() / ("gs_figures_resume_" + std::to_string(::getpid()));
};

TEST_F(FiguresResume, AStoppedJobResumedWritesWhatAJobNeverStoppedWrites) {
  const fs::path never = root_ / "never", stopped = root_ / "stopped";
  ASSERT_FALSE(run_figures_job(tiny(never)).interrupted);

  FiguresOptions o = tiny(stopped);
  o.progress = [] { return std::make_unique<StopAt>(4); };
  ASSERT_TRUE(run_figures_job(o).interrupted);
  clear_stop();
  EXPECT_TRUE(is_unfinished_figures_folder(stopped));
  EXPECT_EQ(text_of(stopped / "figures.toml"), "tiny = true\n");
  // A new job into it would start the ensembles again: refused, naming the way on.
  try {
    run_figures_job(tiny(stopped));
    ADD_FAILURE() << "a new job into an unfinished figures folder was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("grainshock resume"), std::string::npos) << e.what();
  }

  o = tiny(stopped);
  o.resume = true;
  ASSERT_FALSE(run_figures_job(o).interrupted);
  EXPECT_FALSE(is_unfinished_figures_folder(stopped));
  EXPECT_TRUE(results_of(stopped) == results_of(never)) << "the resumed job's results differ";
  const Json j = Json::parse(text_of(stopped / "summary.json"));
  EXPECT_GE(j.at("resumed_realisations").get<int>(), 4);
  // Each ensemble's timing counts the realisations this call ran, not those read back.
  std::int64_t run_after = 0, run_never = 0;
  for (const auto& e : fs::directory_iterator(stopped / "ensembles")) {
    // Kept past the end, for a newer build to fit again
    // (CliFigures.TinyRunWritesEveryPromisedFile).
    EXPECT_TRUE(fs::exists(e.path() / "realisations" / "000000")) << e.path();
    run_after += Json::parse(text_of(e.path() / "timing.json")).at("realisations_run").get<int>();
    run_never += Json::parse(text_of(never / "ensembles" / e.path().filename() / "timing.json"))
                     .at("realisations_run")
                     .get<int>();
  }
  EXPECT_EQ(run_after, run_never - j.at("resumed_realisations").get<int>());

  EXPECT_THROW(run_figures_job(o), UserError);  // finished: nothing to resume
}

TEST_F(FiguresResume, RealisationsOfAnotherPlanOfACaseAreRefused) {
  const fs::path dir = root_ / "f";
  FiguresOptions o = tiny(dir);
  o.progress = [] { return std::make_unique<StopAt>(1); };
  ASSERT_TRUE(run_figures_job(o).interrupted);
  clear_stop();
  // As if another version had planned the first case otherwise.
  const fs::path spec = dir / "ensembles" / "d2_r0.1" / "realisations" / "case.toml";
  ASSERT_TRUE(fs::exists(spec));
  std::ofstream(spec, std::ios::app) << "# another plan\n";
  o.progress = {};
  o.resume = true;
  try {
    run_figures_job(o);
    ADD_FAILURE() << "realisations of another plan were read";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("d2_r0.1"), std::string::npos) << e.what();
  }
}

TEST_F(FiguresResume, AFolderWithoutAnUnfinishedJobIsNotResumed) {
  FiguresOptions o = tiny(root_);
  o.resume = true;
  EXPECT_THROW(run_figures_job(o), UserError);
  EXPECT_TRUE(fs::is_empty(root_));
}

}  // namespace
}  // namespace gs::jobs
