// The cloud march's knob table (shaders/clouds/cloud_march_knobs.def): the docs come from it, its scene paths
// agree with the scene schema, and a value out of a knob's range is an InputError (exit code 2).
#include <gtest/gtest.h>
#include <fstream>
#include <set>
#include <sstream>
#include "clouds/cloud_knobs.h"
#include "clouds/cloud_settings.h"
#include "core/error.h"
#include "core/scene.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

std::string inputErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CloudKnobs, DocsAreGeneratedFromTheTable) {
  std::ifstream in(test::sourceDir() / "docs" / "clouds" / "knobs.md");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), cloudMarchKnobsMarkdown())
      << "docs/clouds/knobs.md is stale: regenerate with `build/samples/firmament cloud-knobs > docs/clouds/knobs.md`";
}

// Identifiers are unique; a default lies in its range; a knob with a scene path is a leaf of the scene
// schema whose allowed values lie in the table's range (the schema checks the scene, the table the code).
TEST(CloudKnobs, IdentifiersAreUniqueAndScenePathsAgreeWithTheSchema) {
  std::set<std::string> ids;
  size_t withScene = 0;
  for (const CloudKnob& k : cloudMarchKnobs()) {
    EXPECT_TRUE(ids.insert(k.id).second) << k.id;
    EXPECT_LE(k.min, k.max) << k.id;
    if (std::string(k.type) == "int" || std::string(k.type) == "double") {
      const double v = std::stod(k.value);
      EXPECT_TRUE(v >= k.min && v <= k.max) << k.id << " " << k.value;
    }
    if (!*k.scene) continue;
    ++withScene;
    const nlohmann::json* leaf = &sceneSchema();
    std::stringstream path(std::string(k.scene).substr(1));
    for (std::string part; std::getline(path, part, '/');) {
      ASSERT_TRUE((*leaf)["properties"].contains(part)) << k.id << ": " << k.scene;
      leaf = &(*leaf)["properties"][part];
    }
    if (leaf->contains("enum") && (std::string(k.type) == "int")) {
      for (const auto& e : (*leaf)["enum"]) {
        EXPECT_TRUE(e.get<double>() >= k.min && e.get<double>() <= k.max) << k.id;
      }
    }
    if (std::string(k.type) == "bool") {
      EXPECT_EQ((*leaf)["type"], "boolean") << k.id;
    }
    if (std::string(k.type) == "AerialPerspective") {
      for (const auto& e : (*leaf)["enum"]) {
        EXPECT_NO_THROW(aerialPerspectiveFromName(e.get<std::string>())) << k.id;
      }
    }
  }
  EXPECT_EQ(withScene, 5u);
  EXPECT_EQ(cloudKnobIdentifier("maxDistance_m"), "max_distance_m");
  EXPECT_EQ(cloudKnobIdentifier("lightSteps"), "light_steps");
}

// Out of range from code is an InputError naming the knob and its range; by identifier a knob is set
// from text, and an unknown identifier or a value that does not parse is an error too.
TEST(CloudKnobs, OverridesCheckRangesAndSetByIdentifier) {
  CloudMarchSettings march;
  CloudOverrides o;
  o.lightSteps = 0;
  const std::string low = inputErrorOf([&] { o.apply(march); });
  EXPECT_NE(low.find("light_steps"), std::string::npos) << low;
  EXPECT_NE(low.find("[1, 256]"), std::string::npos) << low;
  o.lightSteps.reset();
  o.earlyExitTransmittance = 1.5;
  EXPECT_NE(inputErrorOf([&] { o.apply(march); }).find("early_exit_transmittance"), std::string::npos);
  CloudOverrides byName;
  byName.set("light_steps", "8");
  byName.set("deep_shadow_map", "false");
  byName.set("noise_lod_scale", "0.5");
  byName.set("aerial_perspective", "march");
  byName.apply(march);
  EXPECT_EQ(march.lightSteps, 8);
  EXPECT_FALSE(march.deepShadowMap);
  EXPECT_EQ(march.noiseLodScale, 0.5);
  EXPECT_EQ(march.aerialPerspective, AerialPerspective::March);
  EXPECT_NE(inputErrorOf([&] { byName.set("no_such_knob", "1"); }).find("unknown cloud knob"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { byName.set("light_steps", "8.5"); }).find("not an integer"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { byName.set("jitter", "yes"); }).find("true, false"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { byName.set("view_steps", "0"); }).find("out of range"), std::string::npos);
}

}  // namespace
}  // namespace firmament
