#include "tests/support/test_paths.h"

#include <string>

namespace firmament::test {
std::filesystem::path sourceDir() { return FIRMAMENT_SOURCE_DIR; }
std::filesystem::path sharedDataDir() { return sourceDir().parent_path() / "shared" / "data"; }
std::filesystem::path scratchDir(const std::string& name) {
  auto dir = std::filesystem::path(FIRMAMENT_BINARY_DIR) / "test-scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}
}  // namespace firmament::test
