#pragma once
// Small helpers shared by the standalone benchmarks in bench/.
#include "core/error.h"
#include "core/statistics.h"

namespace firmament::bench {

using ::firmament::median;              // core/statistics.h
using ::firmament::runReportingErrors;  // core/error.h

}  // namespace firmament::bench
