#pragma once
// Shared by the terrain tests: the DEM folder the fixture fills, and small field builders.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include "terrain/height_field.h"

namespace firmament::terrain::test {

inline constexpr double kR = 6360e3;  // the atmosphere's ground radius (Bruneton 2017)

// The DEMs fetched by scripts/fetch_test_dems.sh (CTest fixture terrain_test_data). A missing file
// fails the test with the command that fetches it.
inline std::filesystem::path demFile(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(FIRMAMENT_TEST_DEM_DIR) / relative;
  if (!std::filesystem::exists(path))
    ADD_FAILURE() << path << " is missing: run scripts/fetch_test_dems.sh " << FIRMAMENT_TEST_DEM_DIR
                  << " (ctest runs it as the fixture terrain_test_data)";
  return path;
}

// A field of n × n samples over [-half, half]² with heights from a function of the plane point.
inline HeightField makeField(int n, double half, const std::function<double(double, double)>& height,
                             double outside = std::nan("")) {
  HeightField f(n, n, -half, -half, 2.0 * half / (n - 1), 2.0 * half / (n - 1));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) f.at(i, j) = float(height(f.xAt(i), f.yAt(j)));
  f.outsideHeight = outside;
  return f;
}

}  // namespace firmament::terrain::test
