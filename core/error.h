#pragma once
// Error kinds (include/firmament/error.h, public) and the tool's mapping of them to exit codes.
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "firmament/error.h"  // InputError, RuntimeError, the exit codes

namespace firmament {

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
