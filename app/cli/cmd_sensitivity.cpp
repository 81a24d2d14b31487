// fovea-cli sensitivity SCENE --parameter PATH --from A --to B --steps N --json: FOV, mean
// efficiency and efficiency uniformity over values of any numeric scene parameter (a JSON
// path into the scene file, e.g. eye.relief_mm, hoe_layers[1].shrinkage_percent).
// Options: the "sensitivity" analysis of the registry (model/analysis/study_analyses.cpp).
#include <iomanip>
#include <iostream>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/study_cli.h"

namespace fovea::cli {
namespace cmd_sensitivity {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("sensitivity", "FOV and efficiency over values of one scene parameter (JSON path)");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false), no_cache = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  const auto options = addAnalysisOptions(cmd, "sensitivity");
  cmd->add_flag("--json", *json, "print JSON");
  addNoCacheFlag(cmd, *no_cache);
  cmd->callback([=] {
    const nlohmann::json values = options->values();
    const Scene scene = loadSceneOrExit(*path);
    const nlohmann::json out = cachedStudy("sensitivity", values, scene, *no_cache,
                                           [&] { return runStudy(options->definition(), scene, values); });
    if (*json) {
      printJson(out);
      return;
    }
    std::cout << values["parameter"].get<std::string>() << "  fov_h  fov_v  mean_eff  uniformity\n"
              << std::fixed << std::setprecision(3);
    for (const auto& s : out["samples"])
      std::cout << s["value"].get<double>() << "  " << s["fov_deg"]["horizontal"].get<double>() << "  "
                << s["fov_deg"]["vertical"].get<double>() << "  " << s["mean_efficiency"].get<double>() << "  "
                << s["efficiency_uniformity"].get<double>() << "\n";
  });
}

const Registrar reg{"sensitivity", &install};

}  // namespace
}  // namespace cmd_sensitivity
}  // namespace fovea::cli
