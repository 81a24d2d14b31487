// fovea-cli compare-shift SCENE --json: HOE shift vs point-source shift (supplement A.4):
// gaze range covered, travel needed and eye box of each method under the same conditions.
// Options: the "compare-shift" analysis of the registry (model/analysis/study_analyses.cpp);
// --eye left|right|both: each eye of a binocular scene (app/cli/eye_option.h).
#include <iostream>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "app/cli/study_cli.h"

namespace fovea::cli {
namespace cmd_compare_shift {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("compare-shift", "Dynamic eye box: moving the HOE vs moving the projector point source");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false), no_cache = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  const auto options = addAnalysisOptions(cmd, "compare-shift");
  cmd->add_flag("--json", *json, "print JSON");
  addNoCacheFlag(cmd, *no_cache);
  const auto eye = addEyeOption(cmd);
  cmd->callback([=] {
    const nlohmann::json values = options->values();
    const std::vector<EyeRun> runs = eyeRuns(loadSceneOrExit(*path), *eye, *path);
    std::vector<nlohmann::json> docs;
    for (const EyeRun& run : runs)
      docs.push_back(cachedStudy("compare-shift", values, run.scene, *no_cache,
                                 [&] { return runStudy(options->definition(), run.scene, values); }));
    if (*json) {
      printJson(combineEyeDocuments(runs, docs));
      return;
    }
    for (std::size_t i = 0; i < runs.size(); ++i)
      for (const char* k : {"hoe_shift", "source_shift"}) {
        const auto& e = docs[i][k];
        std::cout << eyePrefix(runs[i]) << k << ": gaze " << e["gaze_range_deg"][0] << " .. " << e["gaze_range_deg"][1]
                  << " deg, travel " << e["travel_mm"][0] << " .. " << e["travel_mm"][1] << " mm, eye box "
                  << e["eyebox_mm"] << " mm\n";
      }
  });
}

const Registrar reg{"compare-shift", &install};

}  // namespace
}  // namespace cmd_compare_shift
}  // namespace fovea::cli
