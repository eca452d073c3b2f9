#include "core/log.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace firmament {
namespace {
LogLevel gLevel = LogLevel::Info;
}

void setLogLevel(LogLevel level) { gLevel = level; }
LogLevel logLevel() { return gLevel; }

void logInfo(std::string_view message) {
  if (gLevel >= LogLevel::Info) std::fprintf(stderr, "%.*s\n", int(message.size()), message.data());
}
void logVerbose(std::string_view message) {
  if (gLevel >= LogLevel::Verbose) std::fprintf(stderr, "%.*s\n", int(message.size()), message.data());
}
void logWarning(std::string_view message) {
  std::fprintf(stderr, "warning: %.*s\n", int(message.size()), message.data());
}

Progress::Progress(std::string label, uint64_t total)
    : label_(std::move(label)), total_(total ? total : 1), start_(std::chrono::steady_clock::now()) {
  const char* forced = std::getenv("FIRMAMENT_PROGRESS");
  enabled_ = gLevel >= LogLevel::Info && (forced ? std::strcmp(forced, "0") != 0 : isatty(fileno(stderr)) != 0);
  lastDraw_ = start_;
}

Progress::~Progress() {
  if (drawn_) draw(true);
}

void Progress::advance(uint64_t steps) { set(done_ + steps); }

void Progress::set(uint64_t done) {
  done_ = done > total_ ? total_ : done;
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  // Quiet for the first second; then redraw at most 10 times a second.
  if (now - start_ < std::chrono::seconds(1)) return;
  if (drawn_ && now - lastDraw_ < std::chrono::milliseconds(100) && done_ != total_) return;
  lastDraw_ = now;
  draw(false);
}

void Progress::draw(bool final) {
  constexpr int kWidth = 30;
  double fraction = double(done_) / double(total_);
  int filled = int(fraction * kWidth);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string bar(size_t(filled), '=');
  if (filled < kWidth) bar += '>';
  bar.resize(kWidth, ' ');
  std::fprintf(stderr, "\r%s [%s] %3d%% %.1f s%s", label_.c_str(), bar.c_str(), int(fraction * 100.0), seconds,
               final ? "\n" : "");
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace firmament
