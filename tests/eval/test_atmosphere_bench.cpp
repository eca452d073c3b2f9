// `bench atmosphere` machinery on a tiny configuration: one scenario at 16x9, one knob with two
// values. Checks results.csv's columns and rows, the report and plots, the reference cache, and
// that the error falls as a quality knob rises (view steps 4 -> 64).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "eval/atmosphere_bench.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

// Splits one CSV line (RFC 4180 quoting).
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
      fields.back() += '"', ++i;
    else if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      fields.emplace_back();
    else
      fields.back() += c;
  }
  return fields;
}

std::vector<std::vector<std::string>> readCsv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(splitCsv(line));
  return rows;
}

AtmosphereBenchConfig tinyConfig(const std::filesystem::path& out) {
  AtmosphereBenchConfig config;
  config.outDir = out;
  BenchScenario noon = atmosphereBenchScenarios(true).front();
  EXPECT_EQ(noon.name, "noon");
  noon.width = 16, noon.height = 9, noon.referenceSamples = 256;
  config.scenarios = {noon};
  for (auto& knob : atmosphereBenchKnobs(false))
    if (knob.name == "view_steps") {
      std::vector<BenchKnobValue> kept;
      for (auto& v : knob.values)
        if (v.value == "4" || v.value == "64") kept.push_back(v);
      knob.values = kept;
      config.knobs.push_back(knob);
    }
  config.repeats = 1;
  config.fullFrameTiming = false;
  return config;
}

TEST(AtmosphereBench, TinySweepWritesTheCsvAndErrorFallsWithViewSteps) {
  const auto out = test::scratchDir("atmosphere-bench");
  gpu::ContextOptions options;
  options.persistentPipelineCache = false;  // no disk cache: the tables are recomputed each repeat
  gpu::Context context(options);

  AtmosphereBenchConfig config = tinyConfig(out);
  ASSERT_EQ(config.knobs.size(), 1u);
  ASSERT_EQ(config.knobs[0].values.size(), 2u);
  const AtmosphereBenchResult result = runAtmosphereBench(context, config);
  writeAtmosphereBenchOutputs(config, result);
  EXPECT_TRUE(context.validationMessages().empty());

  const auto rows = readCsv(out / "results.csv");
  ASSERT_EQ(rows.size(), 4u);  // header, default, view_steps 4 and 64
  EXPECT_EQ(rows[0], (std::vector<std::string>{"knob", "value", "scenario", "precompute_ms", "frame_ms", "rel_rmse",
                                               "psnr_db", "max_rel_err", "device"}));
  EXPECT_EQ(rows[1][0], "default");
  EXPECT_EQ(rows[1][1], "default");
  double rel4 = NAN, rel64 = NAN;
  for (size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 9u) << "row " << i;
    EXPECT_EQ(rows[i][2], "noon");
    for (int c = 3; c <= 7; ++c) EXPECT_TRUE(std::isfinite(std::stod(rows[i][c]))) << rows[i][c];
    EXPECT_GT(std::stod(rows[i][3]), 0.0);  // precompute_ms
    EXPECT_GT(std::stod(rows[i][4]), 0.0);  // frame_ms
    EXPECT_EQ(rows[i][8], context.description());
    if (rows[i][0] == "view_steps" && rows[i][1] == "4") rel4 = std::stod(rows[i][5]);
    if (rows[i][0] == "view_steps" && rows[i][1] == "64") rel64 = std::stod(rows[i][5]);
  }
  EXPECT_LT(rel64, rel4) << "more march steps must bring the fast path closer to the reference";
  EXPECT_LT(rel64, 0.2);

  EXPECT_TRUE(std::filesystem::exists(out / "report.md"));
  EXPECT_TRUE(std::filesystem::exists(out / "plot_noon_frame.svg"));
  ASSERT_EQ(result.references.size(), 1u);
  EXPECT_FALSE(result.references[0].fromCache);
  EXPECT_GT(result.references[0].noiseRelRmse, 0.0);

  // A second run reads the reference from the cache.
  config.knobs.clear();
  const AtmosphereBenchResult again = runAtmosphereBench(context, config);
  ASSERT_EQ(again.references.size(), 1u);
  EXPECT_TRUE(again.references[0].fromCache);
  EXPECT_DOUBLE_EQ(again.rows[0].relRmse, result.rows[0].relRmse);
}

TEST(AtmosphereBench, MaxRelativeErrorUsesTheFloorForDarkPixels) {
  Image reference(2, 1, 4), test(2, 1, 4);
  for (int c = 0; c < 3; ++c) {
    reference.at(0, 0)[c] = 100.0f, test.at(0, 0)[c] = 110.0f;  // 10 % off
    reference.at(1, 0)[c] = 0.0f, test.at(1, 0)[c] = 0.25f;     // black: measured against ε = 0.5
  }
  EXPECT_NEAR(maxRelativeLuminanceError(test, reference), 0.5, 1e-5);
}

}  // namespace
}  // namespace firmament
