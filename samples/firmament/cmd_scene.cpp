// `firmament check SCENE` validates a scene and prints it with every default filled in;
// `firmament scene-doc` prints docs/scene.md, generated from the embedded schema;
// `firmament cloud-knobs` prints docs/clouds/knobs.md, generated from the cloud march's knob table.
#include <cstdio>

#include "clouds/cloud_knobs.h"
#include "core/scene.h"
#include "samples/firmament/command.h"

namespace firmament::cli {
namespace {

int runCheck(const Args& args) {
  Scene scene = Scene::load(args.positionals.at(0), args.all("set"));
  std::printf("%s\n", scene.root().dump(2).c_str());
  std::fprintf(stderr, "%s: valid (hash %s)\n", scene.source().c_str(), scene.hash().c_str());
  return 0;
}

int runSceneDoc(const Args&) {
  std::fputs(sceneSchemaMarkdown().c_str(), stdout);
  return 0;
}

int runCloudKnobs(const Args&) {
  std::fputs(cloudMarchKnobsMarkdown().c_str(), stdout);
  return 0;
}

const CommandRegistration check{{"check",
                                 "validate a scene file and print it with defaults filled in",
                                 "check SCENE [--set /PATH=VALUE]...",
                                 {setOption()},
                                 1,
                                 1,
                                 runCheck}};
const CommandRegistration sceneDoc{
    {"scene-doc", "print the scene-format reference (docs/scene.md) in Markdown", "scene-doc", {}, 0, 0, runSceneDoc}};
const CommandRegistration cloudKnobs{{"cloud-knobs",
                                      "print the cloud march's knobs (docs/clouds/knobs.md) in Markdown",
                                      "cloud-knobs",
                                      {},
                                      0,
                                      0,
                                      runCloudKnobs}};

}  // namespace
}  // namespace firmament::cli
