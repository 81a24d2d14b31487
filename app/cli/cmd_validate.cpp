// fovea-cli validate SCENE: exit 0 with a one-line summary, or exit 1 listing every problem.
#include <iostream>

#include "app/cli/cli_common.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace cmd_validate {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("validate", "Check a scene file; print a summary or every problem found");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file")->required();
  cmd->add_flag("--json", *json, "print {\"valid\":…, \"errors\":[…], \"warnings\":[…], \"summary\":…}");
  cmd->callback([path, json] {
    SceneLoadResult r = loadSceneFile(*path);
    if (*json) {
      nlohmann::json out{{"valid", r.ok()}, {"errors", r.errors}, {"warnings", r.warnings}};
      if (r.ok()) out["summary"] = sceneSummary(*r.scene);
      printJson(out);
      if (!r.ok()) throw CliError(1, std::to_string(r.errors.size()) + " problem(s) in " + *path);
      return;
    }
    for (const auto& w : r.warnings) std::cerr << "warning: " << w << "\n";
    if (!r.ok()) {
      for (const auto& e : r.errors) std::cout << e << "\n";
      throw CliError(1, std::to_string(r.errors.size()) + " problem(s) in " + *path);
    }
    std::cout << *path << ": valid: " << sceneSummary(*r.scene) << "\n";
  });
}

const Registrar reg{"validate", &install};

}  // namespace
}  // namespace cmd_validate
}  // namespace fovea::cli
