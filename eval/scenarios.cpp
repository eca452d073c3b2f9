#include "eval/scenarios.h"

#include <span>
#include <stdexcept>

#include "core/embedded_file.h"

namespace firmament {

std::span<const EmbeddedFile> evalScenarioFiles();  // generated (cmake/EmbedFiles.cmake)

std::string_view evalScenarioText(const std::string& path) {
  for (const EmbeddedFile& f : evalScenarioFiles())
    if (f.path == path) return f.text;
  throw std::logic_error("eval/scenarios/" + path + " is not built in (eval/CMakeLists.txt)");
}

nlohmann::json evalScenarioIndex(const std::string& group) {
  return nlohmann::json::parse(evalScenarioText(group + "/index.json"));
}

Scene evalScenarioScene(const std::string& group, const std::string& name, const std::vector<std::string>& overrides) {
  const std::string path = group + "/" + name + ".json";
  return Scene::parse(evalScenarioText(path), "eval/scenarios/" + path, overrides);
}

std::vector<std::string> evalScenarioPaths() {
  std::vector<std::string> paths;
  for (const EmbeddedFile& f : evalScenarioFiles()) paths.emplace_back(f.path);
  return paths;
}

}  // namespace firmament
