// A scene compiles to the passes it needs and no others.
#include <gtest/gtest.h>

#include "sky/render_plan.h"

namespace firmament {
namespace {

TEST(RenderPlan, ClearSkyRunsNoCloudPasses) {
  RenderPlan plan = planRender(Scene::parse("{}", "<test>"));
  EXPECT_TRUE(plan.has("atmosphere/transmittance_lut"));
  EXPECT_TRUE(plan.has("sky/render_sky"));
  for (const auto& p : plan.passes) EXPECT_EQ(p.name.rfind("clouds/", 0), std::string::npos) << p.name;
  bool cloudsOmitted = false;
  for (const auto& o : plan.omitted) cloudsOmitted = cloudsOmitted || o.name == "clouds";
  EXPECT_TRUE(cloudsOmitted);
}

TEST(RenderPlan, ExplainListsPassesInOrder) {
  std::string text = describePlan(planRender(Scene::parse("{}", "<test>")));
  auto lut = text.find("atmosphere/transmittance_lut");
  auto sky = text.find("sky/render_sky");
  ASSERT_NE(lut, std::string::npos);
  ASSERT_NE(sky, std::string::npos);
  EXPECT_LT(lut, sky);
  EXPECT_NE(text.find("left out"), std::string::npos);
}

TEST(RenderPlan, RequestedButUnavailableIsReported) {
  // Terrain is drawn on the f_ms path; with the 4D tables it is reported as unavailable.
  PlanOptions tables;
  tables.multipleScattering = MultipleScattering::BrunetonTables;
  RenderPlan plan = planRender(Scene::parse(R"({"terrain": {}})", "<test>"), tables);
  ASSERT_FALSE(plan.unavailable.empty());
  EXPECT_EQ(plan.unavailable[0].name, "terrain");
}

}  // namespace
}  // namespace firmament
