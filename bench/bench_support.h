#pragma once
// Small helpers shared by the standalone benchmarks in bench/.
#include "core/statistics.h"

namespace firmament::bench {

using ::firmament::median;  // core/statistics.h

}  // namespace firmament::bench
