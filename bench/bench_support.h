#pragma once
// Small helpers shared by the standalone benchmarks in bench/.
#include <cstdio>
#include <exception>

#include "core/error.h"
#include "core/statistics.h"

namespace firmament::bench {

using ::firmament::median;  // core/statistics.h

// A benchmark's main body, with the tool's exit codes: a bad argument or scene (InputError) prints its
// message and gives kExitBadInput, any other failure kExitRuntime.
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

}  // namespace firmament::bench
