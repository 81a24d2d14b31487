// fovea-cli optimize-lens SCENE [--catalog FILE] [--apply OUT] --json: choose the stock
// beam-shaping lens, position and Scheimpflug tilt minimising the RMS pixel spot on the
// HOE (supplement A.2). NLopt BOBYQA from several starts per catalogue lens.
// Options: the "optimize-lens" analysis of the registry (model/analysis/study_analyses.cpp)
// plus --catalog and --apply, which only the command line has.
#include <iostream>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/study_cli.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/beam_shaping.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace cmd_optimize_lens {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "optimize-lens",
      "Optimise a stock beam-shaping lens (focal length, position, tilt) for the sharpest pixels on the HOE");
  auto path = std::make_shared<std::string>();
  auto catalog = std::make_shared<std::string>();
  auto apply = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto no_cache = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--catalog", *catalog, "lens catalogue JSON (default: the shipped resources/lenses/catalog.json)");
  const auto options = addAnalysisOptions(cmd, "optimize-lens");
  auto* apply_option =
      cmd->add_option("--apply", *apply, "write the scene with the optimised lens enabled to this file");
  cmd->add_flag("--json", *json, "print JSON");
  addNoCacheFlag(cmd, *no_cache);
  cmd->callback([path, catalog, apply, options, json, no_cache, apply_option] {
    checkOutputOption(apply_option, *apply);
    const nlohmann::json values = options->values();
    const Scene scene = loadSceneOrExit(*path);
    std::vector<StockLens> lenses;
    try {
      lenses = catalog->empty() ? defaultLensCatalog() : loadLensCatalogFile(*catalog);
    } catch (const LensCatalogError& e) {
      inputError(e.what());
    }
    nlohmann::json catalog_json = nlohmann::json::array();
    for (const auto& l : lenses)
      catalog_json.push_back({l.part, l.shape, l.glass, l.focal_length_mm, l.diameter_mm, l.center_thickness_mm});
    nlohmann::json params = values;
    params["catalog"] = catalog_json;
    const nlohmann::json out = cachedStudy("optimize-lens", params, scene, *no_cache, [&] {
      LensOptimizationOptions opt;
      opt.starts_per_lens = analysis::integerOf(values, "starts");
      opt.max_distance_mm = analysis::optionalNumberOf(values, "max-distance-mm");
      Progress progress("optimize-lens");
      StudyControl control;
      control.on_progress = [&progress](double f) { progress.update(f); };
      const auto outcome = optimizeBeamShapingLens(scene, lenses, opt, control);
      if (!outcome.ok()) inputError("lens optimisation did not complete");
      return lensOptimizationJson(*outcome.value);
    });
    if (!apply->empty()) {
      Scene shaped = scene;
      shaped.lens.enabled = true;
      shaped.lens.name = out["vendor"].get<std::string>() + " " + out["part"].get<std::string>();
      shaped.lens.pose.position_mm = out["position_mm"].get<Vec3mm>();
      shaped.lens.pose.rotation_deg = out["rotation_deg"].get<std::array<double, 3>>();
      shaped.lens.focal_length_mm = out["focal_length_mm"];
      shaped.lens.diameter_mm = out["diameter_mm"];
      shaped.lens.center_thickness_mm = out["center_thickness_mm"];
      shaped.lens.index = out["index_d"];
      try {
        saveSceneFileAtomic(shaped, *apply);
      } catch (const SceneIoError& e) {
        inputError(e.what());
      }
    }
    if (*json) {
      printJson(out);
      return;
    }
    std::cout << "best lens: " << out["vendor"].get<std::string>() << " " << out["part"].get<std::string>()
              << " f=" << out["focal_length_mm"] << " mm, distance " << out["distance_mm"] << " mm, decentre "
              << out["decenter_mm"] << " mm, tilt " << out["tilt_deg"]
              << " deg\nRMS spot on the HOE: " << out["rms_spot_um"]["before"] << " um -> "
              << out["rms_spot_um"]["after"] << " um (" << out["improvement_percent"] << " % sharper)\n";
  });
}

const Registrar reg{"optimize-lens", &install};

}  // namespace
}  // namespace cmd_optimize_lens
}  // namespace fovea::cli
