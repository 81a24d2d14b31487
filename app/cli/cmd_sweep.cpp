// fovea-cli sweep SCENE --gaze-from A --gaze-to B --gaze-step S [--axis yaw|pitch] --json:
// for each gaze the lateral HOE shift maximising the FOV (supplement A.3), and the eye box.
// Options: the "sweep" analysis of the registry (model/analysis/study_analyses.cpp).
// --shard K/N --json prints the part of shard K (model/analysis/sweep_shards.h): its slice of the
// gazes; `fovea-cli merge PARTS... --json` gives the unsharded document. --eye left|right|both:
// each eye of a binocular scene (app/cli/eye_option.h; a shard runs one eye).
#include <iomanip>
#include <iostream>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "app/cli/study_cli.h"
#include "model/analysis/sweep_shards.h"

namespace fovea::cli {
namespace cmd_sweep {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("sweep", "HOE travel vs gaze: the FOV-maximising HOE shift per gaze angle, and the eye box");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false), no_cache = std::make_shared<bool>(false);
  auto shard = std::make_shared<std::string>();
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  const auto options = addAnalysisOptions(cmd, "sweep");
  cmd->add_flag("--json", *json, "print JSON");
  addNoCacheFlag(cmd, *no_cache);
  cmd->add_option("--shard", *shard,
                  "run only shard K/N (0-based) of the gazes and print its part for `fovea-cli merge` (not cached)");
  const auto eye = addEyeOption(cmd);
  cmd->callback([=] {
    const nlohmann::json values = options->values();
    const std::vector<EyeRun> runs = eyeRuns(loadSceneOrExit(*path), *eye, *path);
    if (!shard->empty()) {
      if (runs.size() != 1) usageError("--shard: a shard runs one eye of a binocular scene: give --eye left or right");
      const Scene& scene = runs.front().scene;
      const auto [k, n] = parseShard(*shard);
      Progress progress("sweep");
      StudyControl control;
      control.on_progress = [&progress](double f) { progress.update(f); };
      std::optional<nlohmann::json> part;
      try {
        part = analysis::sweepPartJson(scene, values, k, n, control);
      } catch (const std::invalid_argument& e) {
        usageError(std::string("--") + e.what());
      }
      if (!part) inputError("sweep did not complete");
      if (*json)
        printJson(*part, /*compact=*/true);
      else
        std::cout << "shard " << k << "/" << n << ": " << (*part)["samples"].size()
                  << " gazes (use --json for the part)\n";
      return;
    }
    std::vector<nlohmann::json> docs;
    for (const EyeRun& run : runs)
      docs.push_back(cachedStudy("sweep", values, run.scene, *no_cache,
                                 [&] { return runStudy(options->definition(), run.scene, values); }));
    if (*json) {
      printJson(combineEyeDocuments(runs, docs));
      return;
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const nlohmann::json& out = docs[i];
      if (runs[i].side) std::cout << eyePrefix(runs[i]) << "\n";
      std::cout << "gaze_deg      shift_mm  fov_h  fov_v  fov_d\n" << std::fixed << std::setprecision(2);
      for (const auto& s : out["samples"])
        std::cout << std::setw(8) << s["gaze_deg"].get<double>() << std::setw(14)
                  << (s["hoe_shift_mm"].get<double>() + s["source_shift_mm"].get<double>()) << std::setw(7)
                  << s["fov_deg"]["horizontal"].get<double>() << std::setw(7) << s["fov_deg"]["vertical"].get<double>()
                  << std::setw(7) << s["fov_deg"]["diagonal"].get<double>() << "\n";
      std::cout << "eye box " << out["eyebox_mm"].get<double>() << " mm\n";
    }
  });
}

const Registrar reg{"sweep", &install};

}  // namespace
}  // namespace cmd_sweep
}  // namespace fovea::cli
