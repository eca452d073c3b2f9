// Scene loading: defaults, overrides, and a clear error (file, JSON pointer, found, allowed) for every
// kind of bad input the issue names.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/error.h"
#include "core/scene.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

// Expects an InputError whose message contains every fragment.
void expectInputError(const std::function<void()>& f, const std::vector<std::string>& fragments) {
  try {
    f();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    std::string message = e.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << "message: " << message << "\nmissing: " << fragment;
  }
}

TEST(Scene, DefaultSceneIsValidAndFilled) {
  Scene scene = Scene::load(test::sourceDir() / "scenes" / "default.json");
  EXPECT_DOUBLE_EQ(scene.number("/camera/fov_deg"), 75.0);
  EXPECT_EQ(scene.string("/camera/exposure/tonemap"), "aces");
  EXPECT_DOUBLE_EQ(scene.number("/camera/roll_deg"), 0.0);  // defaulted
  EXPECT_TRUE(scene.hasSection("terrain"));                 // the open-world view: terrain,
  EXPECT_TRUE(scene.hasSection("clouds"));                  // clouds
  EXPECT_TRUE(scene.hasSection("weather"));                 // from the weather simulation
  EXPECT_TRUE(scene.hasSection("atmosphere"));
  const Scene clear = Scene::parse(clearSkyDefaultSceneText(), "clear sky");
  EXPECT_FALSE(clear.hasSection("terrain"));  // optional sections stay out
  EXPECT_FALSE(clear.hasSection("clouds"));
  EXPECT_FALSE(clear.hasSection("weather"));
  EXPECT_EQ(clear.string("/time/utc"), scene.string("/time/utc"));
}

TEST(Scene, EmptyObjectGetsEveryDefault) {
  Scene scene = Scene::parse("{}", "<test>");
  EXPECT_DOUBLE_EQ(scene.number("/location/latitude_deg"), 46.55);
  EXPECT_EQ(scene.integer("/camera/width"), 1280);
  EXPECT_EQ(scene.string("/time/utc"), "2026-06-21T15:30:00Z");
  EXPECT_FALSE(scene.hasSection("weather"));
}

TEST(Scene, ArrayItemsGetDefaults) {
  Scene scene = Scene::parse(R"({"clouds": {"layers": [{"kind": "stratus"}, {}]}})", "<test>");
  EXPECT_EQ(scene.string("/clouds/layers/0/kind"), "stratus");
  EXPECT_DOUBLE_EQ(scene.number("/clouds/layers/1/bottom_m"), 1500.0);
  EXPECT_EQ(scene.string("/clouds/quality"), "default");
}

TEST(Scene, OverridesApplyBeforeValidation) {
  Scene scene =
      Scene::parse("{}", "<test>", {"/camera/fov_deg=60", "/camera/projection=fisheye", "/clouds/layers/0/top_m=5000"});
  EXPECT_DOUBLE_EQ(scene.number("/camera/fov_deg"), 60.0);
  EXPECT_EQ(scene.string("/camera/projection"), "fisheye");
  EXPECT_DOUBLE_EQ(scene.number("/clouds/layers/0/top_m"), 5000.0);
  expectInputError([] { Scene::parse("{}", "<test>", {"/camera/fov_deg=500"}); },
                   {"/camera/fov_deg", "500", "(0, 360]"});
  expectInputError([] { Scene::parse("{}", "<test>", {"camera.fov=3"}); }, {"--set", "/json/pointer=value"});
}

TEST(Scene, UnknownKeyNamesPointerAndAllowedKeys) {
  expectInputError([] { Scene::parse(R"({"camera": {"fov": 60}})", "a.json"); },
                   {"a.json", "/camera/fov", "unknown key", "fov_deg"});
  expectInputError([] { Scene::parse(R"({"colour": 1})", "a.json"); }, {"a.json", "/colour", "unknown key"});
}

// A key of a measured and removed option (the schema's x-removed) is an error that names the key, says it
// was removed and points at the decision record that keeps the finding; every such record exists.
TEST(Scene, RemovedKeyNamesTheKeyAndItsDecision) {
  expectInputError([] { Scene::parse(R"({"clouds": {"top_entry_shadow": true}})", "r.json"); },
                   {"r.json", "/clouds/top_entry_shadow", "removed key", "docs/decisions/0001-"});
  expectInputError([] { Scene::parse(R"({"clouds": {"light_steps_falloff": 1}})", "r.json"); },
                   {"/clouds/light_steps_falloff", "removed key", "docs/decisions/0002-"});
  size_t removed = 0;
  std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& s) {
    if (s.contains("x-removed"))
      for (auto it = s["x-removed"].begin(); it != s["x-removed"].end(); ++it) {
        const std::string why = it.value().get<std::string>();
        const size_t at = why.find("docs/decisions/");
        ASSERT_NE(at, std::string::npos) << it.key();
        const std::string file = why.substr(at, why.find(')', at) - at);
        EXPECT_TRUE(std::filesystem::exists(test::sourceDir() / file)) << it.key() << ": " << file;
        EXPECT_FALSE(s["properties"].contains(it.key())) << it.key();
        ++removed;
      }
    if (s.contains("properties"))
      for (auto it = s["properties"].begin(); it != s["properties"].end(); ++it) walk(it.value());
  };
  walk(sceneSchema());
  EXPECT_EQ(removed, 4u);
}

TEST(Scene, WrongTypeNamesFoundAndAllowed) {
  expectInputError([] { Scene::parse(R"({"camera": {"fov_deg": "wide"}})", "b.json"); },
                   {"b.json", "/camera/fov_deg", "string \"wide\"", "number"});
  expectInputError([] { Scene::parse(R"({"camera": {"width": 12.5}})", "b.json"); }, {"/camera/width", "integer"});
  expectInputError([] { Scene::parse(R"({"camera": 3})", "b.json"); }, {"/camera", "an object"});
  expectInputError([] { Scene::parse(R"([1, 2])", "b.json"); }, {"b.json", "an object"});
}

TEST(Scene, OutOfRangeNamesRange) {
  expectInputError([] { Scene::parse(R"({"clouds": {"layers": [{"bottom_m": -5}]}})", "c.json"); },
                   {"c.json", "/clouds/layers/0/bottom_m", "-5", "[0, 20000]"});
  expectInputError([] { Scene::parse(R"({"camera": {"projection": "orthographic"}})", "c.json"); },
                   {"/camera/projection", "\"perspective\""});
  expectInputError([] { Scene::parse(R"({"time": {"utc": "2026-02-30T00:00:00Z"}})", "c.json"); },
                   {"/time/utc", "UTC date-time"});
  expectInputError([] { Scene::parse(R"({"time": {"utc": "2026-06-21 15:30"}})", "c.json"); }, {"/time/utc"});
}

TEST(Scene, MalformedJsonNamesLineAndColumn) {
  expectInputError([] { Scene::parse("{\n  \"camera\": {,\n}", "d.json"); }, {"d.json", "malformed JSON", "line 2"});
}

TEST(Scene, EmptyAndMissingFiles) {
  auto dir = test::scratchDir("scene_files");
  std::ofstream(dir / "empty.json") << "  \n";
  expectInputError([&] { Scene::load(dir / "empty.json"); }, {"empty.json", "empty"});
  expectInputError([&] { Scene::load(dir / "missing.json"); }, {"missing.json", "no such scene file"});
  expectInputError([&] { Scene::load(dir); }, {"folder"});
}

TEST(Scene, HashIsCanonical) {
  Scene a = Scene::parse(R"({"camera": {"fov_deg": 60, "width": 100}})", "a");
  Scene b = Scene::parse(R"({"camera": {"width": 100, "fov_deg": 60.0}})", "b");
  Scene c = Scene::parse(R"({"camera": {"width": 101, "fov_deg": 60}})", "c");
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_NE(a.hash(), c.hash());
}

TEST(Scene, EveryShippedSceneValidates) {
  for (const auto& entry : std::filesystem::directory_iterator(test::sourceDir() / "scenes"))
    if (entry.path().extension() == ".json") {
      EXPECT_NO_THROW(Scene::load(entry.path())) << entry.path();
    }
}

TEST(Scene, DocsAreGeneratedFromTheSchema) {
  std::ifstream in(test::sourceDir() / "docs" / "scene.md");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), sceneSchemaMarkdown())
      << "docs/scene.md is stale: regenerate with `build/samples/firmament scene-doc > docs/scene.md`";
}

TEST(Scene, EverySchemaFieldHasDefaultAndDescription) {
  std::function<void(const nlohmann::json&, const std::string&)> walk = [&](const nlohmann::json& s,
                                                                            const std::string& p) {
    EXPECT_TRUE(s.contains("description")) << p;
    if (s.value("type", "") == "object") {
      for (auto it = s["properties"].begin(); it != s["properties"].end(); ++it) walk(it.value(), p + "/" + it.key());
    } else if (s.value("type", "") == "array") {
      EXPECT_TRUE(s.contains("default")) << p;
      if (s.contains("items") && s["items"].value("type", "") == "object")
        for (auto it = s["items"]["properties"].begin(); it != s["items"]["properties"].end(); ++it) {
          // a field listed in its object's "required" needs no default
          bool required = false;
          for (const auto& r : s["items"].value("required", nlohmann::json::array()))
            required = required || r == it.key();
          if (!required)
            walk(it.value(), p + "/N/" + it.key());
          else
            EXPECT_TRUE(it.value().contains("description")) << p << "/N/" << it.key();
        }
    } else if (s.value("x-optional-section", false)) {
      // An optional field's default depends on other fields (e.g. the cloud type's calibrated octave
      // parameters): its description must say what its absence means.
      EXPECT_NE(s.value("description", "").find("Absent:"), std::string::npos) << p;
    } else {
      EXPECT_TRUE(s.contains("default")) << p;
    }
  };
  auto schema = sceneSchema();
  for (auto it = schema["properties"].begin(); it != schema["properties"].end(); ++it) walk(it.value(), "/" + it.key());
}

}  // namespace
}  // namespace firmament

namespace firmament {
namespace {
TEST(Scene, BuiltInDefaultMatchesTheFile) {
  Scene file = Scene::load(test::sourceDir() / "scenes" / "default.json");
  Scene builtIn = Scene::parse(defaultSceneText(), kDefaultSceneName);
  EXPECT_EQ(file.hash(), builtIn.hash());
}
}  // namespace
}  // namespace firmament
