#pragma once
// Paths the tests need: the source tree (scenes, data) and a scratch folder per test binary.
#include <filesystem>

namespace firmament::test {
std::filesystem::path sourceDir();
std::filesystem::path sharedDataDir();  // ../shared/data beside the checkout
// A fresh, empty folder under the build tree for this test's files.
std::filesystem::path scratchDir(const std::string& name);
}  // namespace firmament::test
