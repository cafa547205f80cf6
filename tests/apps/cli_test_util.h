#pragma once
// Running the grainshock binary from tests: exit code, stderr lines, scratch folders.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

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

}  // namespace gs::test
