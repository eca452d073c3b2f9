#pragma once
// A scene: the validated JSON of a scene file with every default filled in (docs/scene.md).
//
// Loading reads the file, applies `--set /json/pointer=value` overrides, then validates against the
// embedded schema (core/scene_schema.json). Any problem is an InputError naming the file, the JSON
// pointer, what was found and what is allowed. Optional sections (clouds, weather, terrain, sun)
// stay absent when the file leaves them out: that part of the sky is then not simulated.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace firmament {

class Scene {
 public:
  // Reads and validates a scene file. Throws InputError (missing, unreadable, empty, malformed,
  // invalid).
  static Scene load(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  // Validates scene text; `source` names it in errors (a file name or "<string>").
  static Scene parse(std::string_view text, const std::string& source, const std::vector<std::string>& overrides = {});

  const nlohmann::json& root() const { return root_; }
  const std::string& source() const { return source_; }
  bool hasSection(const std::string& name) const { return root_.contains(name); }

  // Typed access by JSON pointer ("/camera/fov_deg"); the schema guarantees presence for defaulted
  // fields. A missing field or wrong type here is a programming error (std::logic_error).
  double number(const std::string& pointer) const;
  int64_t integer(const std::string& pointer) const;
  std::string string(const std::string& pointer) const;
  bool boolean(const std::string& pointer) const;
  const nlohmann::json& at(const std::string& pointer) const;

  // Hash of the canonical (defaults-filled, key-sorted) JSON: 16 hex digits (FNV-1a 64).
  std::string hash() const;

 private:
  Scene(nlohmann::json root, std::string source) : root_(std::move(root)), source_(std::move(source)) {}
  nlohmann::json root_;
  std::string source_;
};

// Applies one "--set /pointer=value" override to a JSON document. The value is parsed as JSON when
// it is valid JSON (numbers, true/false, quoted strings, arrays, objects), else taken as a string.
// Missing objects on the way are created. Throws InputError for a malformed override.
void applyOverride(nlohmann::json& document, const std::string& override);

// Checks `document` against the scene schema and fills defaults in place. Throws InputError whose
// message starts with "<source>: <pointer>: ".
void validateScene(nlohmann::json& document, const std::string& source);

// scenes/default.json as built into the program (what `render` uses when given no scene).
std::string_view defaultSceneText();
inline constexpr const char* kDefaultSceneName = "scenes/default.json (built in)";

// The default scene's place, time, camera and atmosphere without its terrain, clouds and weather: the
// clear sky that the atmosphere's validation and micro-benchmarks measure.
std::string clearSkyDefaultSceneText();

// The embedded schema and its Markdown rendering (docs/scene.md is generated from it).
const nlohmann::json& sceneSchema();
std::string sceneSchemaMarkdown();

}  // namespace firmament
