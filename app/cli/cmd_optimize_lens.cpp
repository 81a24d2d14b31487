// fovea-cli optimize-lens SCENE [--catalog FILE] [--apply OUT] --json: choose the stock
// beam-shaping lens, position and Scheimpflug tilt minimising the RMS pixel spot on the
// HOE (supplement A.2). NLopt BOBYQA from several starts per catalogue lens.
#include <iostream>

#include "app/cli/cli_common.h"
#include "model/analysis/beam_shaping.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "optimize-lens",
      "Optimise a stock beam-shaping lens (focal length, position, tilt) for the sharpest pixels on the HOE");
  auto path = std::make_shared<std::string>();
  auto catalog = std::make_shared<std::string>();
  auto apply = std::make_shared<std::string>();
  auto starts = std::make_shared<int>(5);
  auto json = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--catalog", *catalog, "lens catalogue JSON (default: the shipped resources/lenses/catalog.json)");
  cmd->add_option("--starts", *starts, "optimiser starts per catalogue lens")->check(CLI::Range(1, 50));
  cmd->add_option("--apply", *apply, "write the scene with the optimised lens enabled to this file");
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([path, catalog, apply, starts, json] {
    const Scene scene = loadSceneOrExit(*path);
    std::vector<StockLens> lenses;
    try {
      lenses = catalog->empty() ? defaultLensCatalog() : loadLensCatalogFile(*catalog);
    } catch (const LensCatalogError& e) {
      inputError(e.what());
    }
    LensOptimizationOptions opt;
    opt.starts_per_lens = *starts;
    Progress progress("optimize-lens");
    StudyControl control;
    control.on_progress = [&progress](double f) { progress.update(f); };
    const auto outcome = optimizeBeamShapingLens(scene, lenses, opt, control);
    if (!outcome.ok()) inputError("lens optimisation did not complete");
    const LensOptimization& r = *outcome.value;
    if (!apply->empty()) {
      Scene shaped = scene;
      shaped.lens.enabled = true;
      shaped.lens.name = r.best.lens.vendor + " " + r.best.lens.part;
      shaped.lens.pose = r.pose;
      shaped.lens.focal_length_mm = r.best.lens.focal_length_mm;
      shaped.lens.diameter_mm = r.best.lens.diameter_mm;
      shaped.lens.center_thickness_mm = r.best.lens.center_thickness_mm;
      shaped.lens.index = glassIndex(r.best.lens.glass, 587.6);
      try {
        saveSceneFileAtomic(shaped, *apply);
      } catch (const SceneIoError& e) {
        inputError(e.what());
      }
    }
    if (*json) {
      nlohmann::json out;
      out["part"] = r.best.lens.part;
      out["vendor"] = r.best.lens.vendor;
      out["focal_length_mm"] = r.best.lens.focal_length_mm;
      out["diameter_mm"] = r.best.lens.diameter_mm;
      out["position_mm"] = r.pose.position_mm;
      out["rotation_deg"] = r.pose.rotation_deg;
      out["tilt_deg"] = r.best.placement.tilt_deg;
      out["distance_mm"] = r.best.placement.distance_mm;
      out["decenter_mm"] = r.best.placement.decenter_mm;
      out["rms_spot_um"] = {{"before", r.rms_before_um}, {"after", r.rms_after_um}};
      out["improvement_percent"] = r.improvement_percent;
      nlohmann::json cands = nlohmann::json::array();
      for (const auto& c : r.candidates)
        cands.push_back({{"part", c.lens.part},
                         {"focal_length_mm", c.lens.focal_length_mm},
                         {"diameter_mm", c.lens.diameter_mm},
                         {"distance_mm", c.placement.distance_mm},
                         {"decenter_mm", c.placement.decenter_mm},
                         {"tilt_deg", c.placement.tilt_deg},
                         {"rms_spot_um", c.rms_spot_um},
                         {"evaluations", c.evaluations}});
      out["candidates"] = cands;
      printJson(out);
      return;
    }
    std::cout << "best lens: " << r.best.lens.vendor << " " << r.best.lens.part << " f=" << r.best.lens.focal_length_mm
              << " mm, distance " << r.best.placement.distance_mm << " mm, decentre " << r.best.placement.decenter_mm
              << " mm, tilt " << r.best.placement.tilt_deg << " deg\nRMS spot on the HOE: " << r.rms_before_um
              << " um -> " << r.rms_after_um << " um (" << r.improvement_percent << " % sharper)\n";
  });
}

const Registrar reg{"optimize-lens", &install};

}  // namespace
}  // namespace fovea::cli
