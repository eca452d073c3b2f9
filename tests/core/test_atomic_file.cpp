// Atomic writes: the target is replaced whole or not at all, and no temporary file is left behind.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/error.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {
namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

size_t fileCount(const fs::path& folder) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++n;
  return n;
}

TEST(AtomicFile, WritesTextAndReplacesExistingFile) {
  const fs::path dir = test::scratchDir("atomic_text");
  const fs::path target = dir / "stats.json";
  writeTextFileAtomically(target, "first");
  EXPECT_EQ(readAll(target), "first");
  writeTextFileAtomically(target, std::string("second\0with nul", 15));
  EXPECT_EQ(readAll(target), std::string("second\0with nul", 15));
  EXPECT_EQ(fileCount(dir), 1u);
}

TEST(AtomicFile, WriterGetsTemporaryPathBesideTargetWithSameExtension) {
  const fs::path dir = test::scratchDir("atomic_tmp_path");
  const fs::path target = dir / "image.exr";
  fs::path seen;
  writeFileAtomically(target, [&](const fs::path& tmp) {
    seen = tmp;
    EXPECT_FALSE(fs::exists(target));  // nothing appears under the target's name before the rename
    std::ofstream(tmp) << "data";
  });
  EXPECT_EQ(seen.parent_path(), target.parent_path());
  EXPECT_EQ(seen.extension(), ".exr");
  EXPECT_NE(seen, target);
  EXPECT_EQ(readAll(target), "data");
  EXPECT_FALSE(fs::exists(seen));
}

TEST(AtomicFile, ThrowingWriterKeepsExistingTargetAndLeavesNoTemporary) {
  const fs::path dir = test::scratchDir("atomic_throw");
  const fs::path target = dir / "preview.png";
  writeTextFileAtomically(target, "precious");
  fs::path tmpSeen;
  EXPECT_THROW(writeFileAtomically(target,
                                   [&](const fs::path& tmp) {
                                     tmpSeen = tmp;
                                     std::ofstream(tmp) << "half-writ";  // a partial file, then failure
                                     throw std::runtime_error("disk on fire");
                                   }),
               std::runtime_error);
  EXPECT_EQ(readAll(target), "precious");
  EXPECT_FALSE(fs::exists(tmpSeen));
  EXPECT_EQ(fileCount(dir), 1u);
}

TEST(AtomicFile, ThrowingWriterCreatesNoTarget) {
  const fs::path dir = test::scratchDir("atomic_throw_new");
  EXPECT_THROW(writeFileAtomically(dir / "new.txt", [](const fs::path&) { throw RuntimeError("no"); }), RuntimeError);
  EXPECT_EQ(fileCount(dir), 0u);
}

TEST(AtomicFile, WriterThatWritesNothingIsAnError) {
  const fs::path dir = test::scratchDir("atomic_nothing");
  writeTextFileAtomically(dir / "keep.txt", "old");
  EXPECT_THROW(writeFileAtomically(dir / "keep.txt", [](const fs::path&) {}), RuntimeError);
  EXPECT_EQ(readAll(dir / "keep.txt"), "old");
  EXPECT_EQ(fileCount(dir), 1u);
}

TEST(AtomicFile, MissingFolderIsInputErrorNamingIt) {
  const fs::path dir = test::scratchDir("atomic_missing");
  const fs::path target = dir / "no_such_folder" / "out.json";
  try {
    writeTextFileAtomically(target, "x");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_folder"), std::string::npos) << e.what();
  }
}

TEST(AtomicFile, RelativePathInCurrentFolder) {
  const fs::path dir = test::scratchDir("atomic_relative");
  const fs::path saved = fs::current_path();
  fs::current_path(dir);
  writeTextFileAtomically("relative.txt", "ok");
  fs::current_path(saved);
  EXPECT_EQ(readAll(dir / "relative.txt"), "ok");
}

}  // namespace
}  // namespace firmament
