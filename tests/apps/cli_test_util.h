#pragma once
// Running the grainshock binary from tests: exit code, stderr lines, scratch folders.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace gs::test {

struct CommandResult {
  int exit_code = -1;
  std::string err, out;
  int err_lines() const {
    int n = 0;
    for (char ch : err) n += ch == '\n';
    return n;
  }
};

inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::path(GRAINSHOCK_TEST_OUTPUT_DIR) / info->test_suite_name() /
             (std::string(info->name()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir.parent_path());
  return dir;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs `PROGRAM ARGS` with stdout and stderr captured; `env` is an optional prefix of VAR=value
// assignments.
inline CommandResult run_program(const std::string& program, const std::string& args,
                                 const std::string& env = "") {
  const auto tmp =
      std::filesystem::temp_directory_path() / ("grainshock_test_" + std::to_string(::getpid()));
  const auto err_file = tmp.string() + ".err", out_file = tmp.string() + ".out";
  const std::string cmd = env + " " + program + " " + args + " >" + out_file + " 2>" + err_file;
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = read_file(err_file);
  r.out = read_file(out_file);
  std::filesystem::remove(err_file);
  std::filesystem::remove(out_file);
  return r;
}

inline CommandResult grainshock(const std::string& args, const std::string& env = "") {
  return run_program(GRAINSHOCK_BINARY, args, env);
}

// ARGS split at spaces, as the shell splits them for grainshock() (test paths have none).
inline std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

// Starts `grainshock ARGS` as a child, stdout to /dev/null and stderr to `err`, for tests that
// signal it. Throws (failing the test) when it cannot start, so no test ever signals pid -1,
// which would reach every process of the user.
inline pid_t spawn_grainshock(const std::string& args, const std::string& err = "/dev/null") {
  std::vector<std::string> argv_words = words(args);
  argv_words.insert(argv_words.begin(), GRAINSHOCK_BINARY);
  std::vector<char*> argv;
  for (auto& w : argv_words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0)
    throw std::runtime_error("cannot start " + argv_words[0] + ": posix_spawn " +
                             std::to_string(rc));
  return pid;
}

// Runs `grainshock COMMAND OPTIONS --checkpoint-every 0.05 --out DIR` and kills it with SIGKILL
// at a random moment (up to `max_delay_ms`) once it has written `DIR/CHECKPOINT`, `kills`
// times, each time going on with `grainshock resume`; then lets the last one end, which must
// succeed.
inline void kill_and_resume(const std::string& command, const std::string& options,
                            const std::filesystem::path& dir, const std::string& checkpoint,
                            int kills, int max_delay_ms, std::mt19937& random) {
  std::string args = command + " " + options + " --checkpoint-every 0.05 --out " + dir.string();
  for (int k = 0; k <= kills; ++k) {
    const pid_t pid = spawn_grainshock(args);
    if (k < kills) {
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
      while (!std::filesystem::exists(dir / checkpoint) &&
             std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      std::this_thread::sleep_for(
          std::chrono::milliseconds(std::uniform_int_distribution<int>(0, max_delay_ms)(random)));
      kill(pid, SIGKILL);
    }
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    if (WIFEXITED(status)) {  // it finished before the kill
      ASSERT_EQ(WEXITSTATUS(status), 0) << args;
      return;
    }
    // Checkpoints are on disk from the first one to the job's very end (a commit keeps the
    // previous until the new one is in place): a kill that finds neither came after the job had
    // removed them. A resume then either clears what the end had left (a movie's parts) or says
    // the job is finished, and there is nothing more to go on with.
    const std::string previous = checkpoint.substr(0, checkpoint.rfind(".bin")) + ".prev.bin";
    if (!std::filesystem::exists(dir / checkpoint) && !std::filesystem::exists(dir / previous)) {
      const CommandResult r = grainshock("resume --quiet " + dir.string());
      if (r.exit_code != 0) {
        ASSERT_NE(r.err.find("holds a finished"), std::string::npos) << r.err;
      }
      return;
    }
    args = "resume --quiet --checkpoint-every 0.05 " + dir.string();
  }
}

}  // namespace gs::test
