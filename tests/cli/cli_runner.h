#pragma once
// Runs the built `firmament` tool (FIRMAMENT_EXE, set by tests/CMakeLists.txt) as a user would and
// returns its exit code and everything it printed.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace firmament::test {

struct CommandRun {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

inline CommandRun firmament(const std::string& arguments) {
  std::string command = std::string(FIRMAMENT_EXE) + " " + arguments + " 2>&1";
  CommandRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), n);
  int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace firmament::test
