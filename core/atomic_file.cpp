#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"

namespace firmament {
namespace fs = std::filesystem;

namespace {

// ".NAME.tmp-PID-N.EXT": hidden, unique per process and call, and keeps the extension.
fs::path temporaryPathFor(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  std::string name(1, '.');
  name.append(target.stem().string()).append(".tmp-").append(std::to_string(::getpid()));
  name.append(1, '-').append(std::to_string(counter.fetch_add(1))).append(target.extension().string());
  return target.parent_path() / name;
}

// Flushes the file's data to the device before the rename, so that after a crash the target is
// either the old file or the complete new one, not an empty file with the new name.
void syncFile(const fs::path& path) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw RuntimeError("cannot open '" + path.string() + "' to flush it: " + std::strerror(errno));
  int rc = ::fsync(fd);
  int savedErrno = errno;
  ::close(fd);
  if (rc != 0) throw RuntimeError("cannot flush '" + path.string() + "' to disk: " + std::strerror(savedErrno));
}

// Makes the rename itself durable. Best effort: some file systems refuse fsync on a folder.
void syncFolder(const fs::path& folder) {
  int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

void writeFileAtomically(const fs::path& target, const std::function<void(const fs::path& tmp)>& writer) {
  if (target.filename().empty()) throw InputError("output path '" + target.string() + "' names no file");
  const fs::path folder = target.parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::is_directory(folder, ec))
    throw InputError("cannot write '" + target.string() + "': folder '" + folder.string() + "' does not exist");
  if (fs::is_directory(target, ec)) throw InputError("cannot write '" + target.string() + "': it is a folder");

  const fs::path tmp = temporaryPathFor(target);
  try {
    writer(tmp);
    if (!fs::is_regular_file(tmp, ec)) throw RuntimeError("writing '" + target.string() + "' produced no file");
    syncFile(tmp);
    fs::rename(tmp, target, ec);
    if (ec) throw RuntimeError("cannot rename '" + tmp.string() + "' to '" + target.string() + "': " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);  // never throws; the original exception is the one that matters
    throw;
  }
  syncFolder(folder);
}

void writeTextFileAtomically(const fs::path& target, std::string_view contents) {
  writeFileAtomically(target, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw RuntimeError("cannot create '" + tmp.string() + "': " + std::strerror(errno));
    out.write(contents.data(), std::streamsize(contents.size()));
    out.close();
    if (!out) throw RuntimeError("cannot write '" + target.string() + "' (disk full?)");
  });
}

}  // namespace firmament
