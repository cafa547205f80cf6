#pragma once
// Where the sim tests write their files: the build tree's test output folder.
#include <filesystem>
#include <string>

namespace gs::test {

inline std::string out_path(const std::string& name) {
  std::filesystem::create_directories(GRAINSHOCK_TEST_OUTPUT_DIR);
  return std::string(GRAINSHOCK_TEST_OUTPUT_DIR) + "/" + name;
}

}  // namespace gs::test
