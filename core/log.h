#pragma once
// Logging to stderr and a progress bar for anything that runs longer than a second.
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

namespace firmament {

enum class LogLevel { Quiet = 0, Info = 1, Verbose = 2 };
void setLogLevel(LogLevel level);
LogLevel logLevel();
void logInfo(std::string_view message);
void logVerbose(std::string_view message);
void logWarning(std::string_view message);

// Draws "label [=====>    ] 42% 3.1 s" on stderr, only once the task has run for a second and only
// when stderr is a terminal or FIRMAMENT_PROGRESS=1; ends the line on destruction.
class Progress {
 public:
  Progress(std::string label, uint64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void advance(uint64_t steps = 1);
  void set(uint64_t done);

 private:
  void draw(bool final);
  std::string label_;
  uint64_t total_;
  uint64_t done_ = 0;
  bool drawn_ = false;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
};

}  // namespace firmament
