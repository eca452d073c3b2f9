// The weather map: channels in range, placement on the sphere, wrap, motion with the wind.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/weather/weather_test_support.h"

using namespace firmament::weather;

TEST(WeatherMap, PlacementWrapAndMotion) {
  WeatherConfig c = test::smallConfig("thunderstorm", 64);
  WeatherModel model(c, test::summerDay());
  model.advance(9 * 3600.0);  // 12:32 local solar time
  RegionPlacement placement{test::kLatitude, test::kLongitude, 6360000.0};
  WeatherMap map = model.map(placement);
  ASSERT_EQ(map.map.width, 64);
  ASSERT_EQ(map.wind.channels, 4);
  EXPECT_DOUBLE_EQ(map.time_s, 9 * 3600.0);

  // The centre maps to (0, 0); a point 1 km east along the parallel maps to ≈ (1000, 0).
  glm::dvec2 centre = map.regionCoordinates(test::kLatitude, test::kLongitude);
  EXPECT_NEAR(centre.x, 0.0, 1e-6);
  EXPECT_NEAR(centre.y, 0.0, 1e-6);
  double dLon = 1000.0 / (6360000.0 * std::cos(test::kLatitude));
  glm::dvec2 east = map.regionCoordinates(test::kLatitude, test::kLongitude + dLon);
  EXPECT_NEAR(east.x, 1000.0, 1.0);
  EXPECT_NEAR(east.y, 0.0, 5.0);
  glm::dvec2 north = map.regionCoordinates(test::kLatitude + 1000.0 / 6360000.0, test::kLongitude);
  EXPECT_NEAR(north.y, 1000.0, 1.0);

  // Periodic: a full region width away gives the same sample; texel centres return the texel.
  glm::dvec2 p(1234.5, -2345.6);
  glm::vec4 a = map.sampleMap(p, map.time_s),
            b = map.sampleMap(p + glm::dvec2(map.width_m(), -2 * map.height_m()), map.time_s);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(a[k], b[k], 1e-3f * (1.0f + std::fabs(a[k])));
  glm::vec4 texel = WeatherMap::sampleImage(map.map, 10.5, 20.5);
  for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(texel[k], map.map.at(10, 20)[k]);

  // Motion: after Δt the pattern has moved by mean wind · Δt.
  double dt = 600.0;
  glm::dvec2 moved = p + map.meanWind_m_s * dt;
  glm::vec4 later = map.sampleMap(moved, map.time_s + dt);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(later[k], a[k], 1e-3f * (1.0f + std::fabs(a[k])));

  // Channels within their ranges; the thunderstorm afternoon has cloud somewhere.
  double maxCover = 0;
  for (size_t i = 0; i < map.map.pixelCount(); ++i) {
    const float* px = map.map.pixels.data() + 4 * i;
    ASSERT_GE(px[0], 0.0f);
    ASSERT_LE(px[0], 1.0f);
    ASSERT_GE(px[1], 0.0f);
    ASSERT_LE(px[1], 1.0f);
    ASSERT_GE(px[2], 0.0f);
    ASSERT_GE(px[3], 0.0f);
    maxCover = std::max(maxCover, double(px[0]));
    if (px[0] > 0.5f) {
      EXPECT_GT(px[3], 0.0f) << "a cloudy texel has a top";
    }
  }
  EXPECT_GT(maxCover, 0.5);
}

TEST(WeatherMap, CloudTypeRamp) {
  EXPECT_NEAR(convectiveCloudType(500.0f, 1500.0f), 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(convectiveCloudType(4000.0f, 5500.0f), 2.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(convectiveCloudType(9000.0f, 10500.0f), 1.0f, 1e-6f);
}
