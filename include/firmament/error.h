#pragma once
// The errors Firmament's API throws, and the exit codes its command-line tool maps them to (docs/cli.md):
// 0 ok, 2 bad input (the user can fix it), 3 runtime or device failure. Includes no other Firmament
// header.
#include <stdexcept>

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

}  // namespace firmament
