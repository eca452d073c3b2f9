#pragma once
// Error kinds and the exit codes the command-line tool maps them to (docs/cli.md):
// 0 ok, 2 bad input (the user can fix it), 3 runtime or device failure.
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

namespace firmament {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitRuntime = 3;

// Bad input: a file, field or argument the user gave. The message names the file, the JSON path
// (or argument), what was found and what is allowed.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A failure that is not the user's input: Vulkan, disk full, out of memory.
class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs a command's body with the tool's exit codes: a bad argument, scene or file (InputError) prints its
// message and gives kExitBadInput, any other failure kExitRuntime. Used by `firmament` and the bench
// tools.
template <class Body>
int runReportingErrors(Body body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitRuntime;
  }
}

}  // namespace firmament
