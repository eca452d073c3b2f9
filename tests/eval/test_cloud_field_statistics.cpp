// The cloud-field statistics (eval/cloud_field_statistics.h) on fields whose answers are known: squares
// and discs have D = 1, quadratic Koch islands D = 1.5 exactly, sizes drawn from a power law give back
// its exponent, and the cutting into clouds follows 4-connectivity with holes in the perimeter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "eval/cloud_field_statistics.h"

namespace firmament {
namespace {

struct Grid {
  int width, height;
  std::vector<uint8_t> mask;
  Grid(int w, int h) : width(w), height(h), mask(size_t(w) * h, 0) {}
  void fillRect(int x0, int y0, int w, int h) {
    for (int j = y0; j < y0 + h; ++j)
      for (int i = x0; i < x0 + w; ++i) mask[size_t(j) * width + i] = 1;
  }
};

TEST(CloudFieldStatistics, SquaresHaveDimensionOneAndTheirExactAreasAndPerimeters) {
  Grid g(400, 60);
  int x = 1;
  for (int side : {4, 6, 9, 13, 20, 30, 45}) {
    g.fillRect(x, 2, side, side);
    x += side + 3;
  }
  const std::vector<CloudObject> clouds = findClouds(g.mask, g.width, g.height, 10.0);
  ASSERT_EQ(clouds.size(), 7u);
  EXPECT_DOUBLE_EQ(clouds.front().area_m2, 45.0 * 45.0 * 100.0);
  EXPECT_DOUBLE_EQ(clouds.front().perimeter_m, 4.0 * 45.0 * 10.0);
  const CloudFieldStatistics s = cloudObjectStatistics(clouds, 10.0);
  EXPECT_EQ(s.cloudsInDimensionFit, 7);  // the smallest, 4 x 4, has 16 pixels: at least the 10 asked
  // P = 4 sqrt(A) exactly: ln P = ln 4 + ln A / 2, so D = 1 to rounding.
  EXPECT_NEAR(s.fractalDimension, 1.0, 1e-12);
  EXPECT_NEAR(s.fractalDimensionError, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.largestSize_m, 450.0);
}

TEST(CloudFieldStatistics, PixelDiscsHaveDimensionOne) {
  Grid g(900, 140);
  int cx = 8;
  for (int r : {6, 9, 13, 19, 27, 38, 55}) {
    cx += r + 2;
    for (int j = 0; j < g.height; ++j)
      for (int i = 0; i < g.width; ++i)
        if (std::pow(i + 0.5 - cx, 2.0) + std::pow(j + 0.5 - 70.0, 2.0) < double(r) * r)
          g.mask[size_t(j) * g.width + i] = 1;
    cx += r + 2;
  }
  const CloudFieldStatistics s = cloudObjectStatistics(findClouds(g.mask, g.width, g.height, 1.0), 1.0);
  ASSERT_EQ(s.clouds, 7);
  // A pixel disc's edge perimeter is 8 r (the staircase's length: 4/π of the circle's), whatever r: D = 1.
  EXPECT_NEAR(s.fractalDimension, 1.0, 0.02);
}

// The quadratic Koch island of generation k: the square F+F+F+F with F -> F+F-F-FF+F+F-F (90° turns),
// 4 * 8^k unit segments on the integer lattice. Each generation keeps the area (the generator's bumps
// up and down cancel) and doubles the perimeter while the segment shrinks 4 times, so for a unit segment
// A = 16^k and P = 4 * 8^k: ln P / ln A -> ln 8 / ln 16, D = 2 * 3/4 = 1.5 exactly.
std::vector<std::pair<int, int>> kochIsland(int generation, int x0, int y0) {
  std::string path = "F+F+F+F";
  for (int k = 0; k < generation; ++k) {
    std::string next;
    for (char c : path) next += c == 'F' ? std::string("F+F-F-FF+F+F-F") : std::string(1, c);
    path = next;
  }
  std::vector<std::pair<int, int>> vertices{{x0, y0}};
  int dx = 1, dy = 0, x = x0, y = y0;
  for (char c : path) {
    if (c == 'F') {
      x += dx, y += dy;
      vertices.push_back({x, y});
    } else if (c == '+') {
      std::swap(dx, dy), dx = -dx;  // turn left
    } else {
      std::swap(dx, dy), dy = -dy;  // turn right
    }
  }
  return vertices;
}

TEST(CloudFieldStatistics, QuadraticKochIslandsHaveDimensionOneAndAHalf) {
  Grid g(1000, 480);
  // An island reaches a third of its side beyond its square on every side: these corners keep them apart.
  const int corner[5] = {0, 10, 30, 80, 260};
  for (int k = 1; k <= 4; ++k) {
    const int side = 1 << (2 * k);  // 4^k unit segments
    const auto v = kochIsland(k, corner[k], 120);
    ASSERT_EQ(v.back(), v.front()) << "the island closes";
    // Shoelace area: the generator keeps the square's.
    double area2 = 0.0;
    for (size_t n = 0; n + 1 < v.size(); ++n)
      area2 += double(v[n].first) * v[n + 1].second - double(v[n + 1].first) * v[n].second;
    EXPECT_DOUBLE_EQ(std::abs(area2) / 2.0, double(side) * side);
    // Fill by scanlines at pixel centres: every edge is axis-parallel on the lattice, so only the vertical
    // ones cross y = j + 1/2, and the pixel cover is the polygon exactly.
    for (int j = 0; j < g.height; ++j) {
      std::vector<int> crossings;
      for (size_t n = 0; n + 1 < v.size(); ++n) {
        const auto [xa, ya] = v[n];
        const auto [xb, yb] = v[n + 1];
        if (xa == xb && (j + 0.5 - ya) * (j + 0.5 - yb) < 0.0) crossings.push_back(xa);
      }
      std::sort(crossings.begin(), crossings.end());
      for (size_t c = 0; c + 1 < crossings.size(); c += 2)
        for (int i = crossings[c]; i < crossings[c + 1]; ++i) g.mask[size_t(j) * g.width + i] = 1;
    }
  }
  const std::vector<CloudObject> clouds = findClouds(g.mask, g.width, g.height, 1.0);
  ASSERT_EQ(clouds.size(), 4u);  // the islands neither touch themselves nor each other
  for (int k = 1; k <= 4; ++k) {
    EXPECT_DOUBLE_EQ(clouds[4 - k].area_m2, std::pow(16.0, k));
    EXPECT_DOUBLE_EQ(clouds[4 - k].perimeter_m, 4.0 * std::pow(8.0, k));
  }
  const CloudFieldStatistics s = cloudObjectStatistics(clouds, 1.0);
  EXPECT_EQ(s.cloudsInDimensionFit, 4);
  EXPECT_NEAR(s.fractalDimension, 1.5, 1e-12);
}

TEST(CloudFieldStatistics, PowerLawSizesGiveBackTheirExponent) {
  // 2000 clouds with L drawn from n(L) ∝ L^-1.8 above 30 m (inverse CDF: L = L_min u^(-1/(β-1))).
  std::mt19937_64 random(12345);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double beta = 1.8, pixel = 10.0, lMin = 3.0 * pixel;
  std::vector<CloudObject> clouds;
  for (int n = 0; n < 2000; ++n) {
    CloudObject c;
    c.size_m = lMin * std::pow(1.0 - uniform(random), -1.0 / (beta - 1.0));
    c.area_m2 = c.size_m * c.size_m;
    c.perimeter_m = 4.0 * c.size_m;
    clouds.push_back(c);
  }
  clouds.push_back({4.0 * pixel * pixel, 8.0 * pixel, 2.0 * pixel, 0.0, false});  // below L_min: left out
  CloudFieldStatisticsOptions options;
  options.minPixelsForSizes = 9;
  const CloudFieldStatistics s = cloudObjectStatistics(clouds, pixel, options);
  EXPECT_EQ(s.cloudsInSizeFit, 2000);
  EXPECT_NEAR(s.sizeExponentError, 0.8 / std::sqrt(2000.0), 0.002);
  // Within 3 standard errors (0.054).
  EXPECT_NEAR(s.sizeExponent, beta, 3.0 * s.sizeExponentError);
}

TEST(CloudFieldStatistics, CloudsAreFourConnectedHolesCountAndEdgesAreFlagged) {
  Grid g(40, 20);
  g.fillRect(2, 2, 3, 3);
  g.fillRect(5, 5, 3, 3);  // touches the first only at a corner: a second cloud
  g.fillRect(12, 2, 7, 7);
  g.mask[size_t(5) * 40 + 15] = 0;  // a one-pixel hole: 4 more edges of perimeter
  g.fillRect(30, 10, 10, 4);        // on the eastern edge
  const std::vector<CloudObject> clouds = findClouds(g.mask, g.width, g.height, 1.0);
  ASSERT_EQ(clouds.size(), 4u);
  EXPECT_DOUBLE_EQ(clouds[0].area_m2, 48.0);
  EXPECT_DOUBLE_EQ(clouds[0].perimeter_m, 28.0 + 4.0);
  EXPECT_FALSE(clouds[0].touchesEdge);
  EXPECT_TRUE(clouds[1].touchesEdge);
  EXPECT_DOUBLE_EQ(clouds[1].area_m2, 40.0);
  EXPECT_FALSE(clouds[2].touchesEdge);
  EXPECT_DOUBLE_EQ(clouds[2].area_m2, 9.0);
  EXPECT_DOUBLE_EQ(clouds[3].area_m2, 9.0);

  CloudColumnField field;
  field.width = 40, field.height = 20, field.pixel_m = 1.0;
  field.opticalDepth.assign(g.mask.begin(), g.mask.end());
  for (float& t : field.opticalDepth) t *= 3.0f;  // τ 3 where cloud, above the threshold 1
  field.top_m.assign(field.opticalDepth.size(), 1500.0f);
  const CloudFieldStatistics s = analyzeCloudField(field);
  EXPECT_DOUBLE_EQ(s.cloudFraction, (48.0 + 40.0 + 18.0) / 800.0);
  EXPECT_EQ(s.clouds, 4);
  EXPECT_DOUBLE_EQ(s.maxTop_m, 1500.0);
}

TEST(CloudFieldStatistics, MalformedFieldsAreRefused) {
  EXPECT_THROW(findClouds(std::vector<uint8_t>(10, 0), 4, 4, 1.0), std::exception);
  CloudColumnField field;
  field.width = 3, field.height = 3, field.pixel_m = 1.0;
  field.opticalDepth.assign(4, 0.0f);
  EXPECT_THROW(analyzeCloudField(field), std::exception);
}

}  // namespace
}  // namespace firmament
