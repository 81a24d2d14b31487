// fovea-cli format SCENE [--in-place]: rewrite a scene in canonical form (key order,
// indentation, unknown keys kept). Prints to stdout, or replaces the file atomically.
#include <iostream>

#include "app/cli/cli_common.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("format", "Rewrite a scene file in canonical form");
  auto path = std::make_shared<std::string>();
  auto inPlace = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file")->required();
  cmd->add_flag("--in-place,-i", *inPlace, "replace the file (atomically) instead of printing");
  cmd->callback([path, inPlace] {
    const Scene scene = loadSceneOrExit(*path);
    if (!*inPlace) {
      std::cout << serializeScene(scene);
      return;
    }
    try {
      saveSceneFileAtomic(scene, *path);
    } catch (const SceneIoError& e) {
      inputError(e.what());
    }
  });
}

const Registrar reg{"format", &install};

}  // namespace
}  // namespace fovea::cli
