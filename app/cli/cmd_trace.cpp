// fovea-cli trace SCENE: projector -> recorded HOE stack -> eye; retinal FOV (contract: docs/physics.md).
// --gaze-deg may repeat: one memoised pipeline (model/physics/trace_pipeline.h) serves every
// gaze and the output is a JSON list, one result per gaze; --stats adds
// "stats":{"stages_recomputed":[...],"evaluations":N} to each result.
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "app/cli/cli_common.h"
#include "model/analysis/analysis_json.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"

namespace fovea::cli {
namespace {

struct TraceArgs {
  std::string scene;
  std::vector<std::string> gazes;
  std::string hoe_shift, polarization = "unpolarized";
  double source_shift_mm = 0.0, wavelength_nm = 0.0, threshold = 0.1;
  int rays = 4000;
  bool json = false, stats = false, cull = false;
};

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("trace", "Trace the projector through the recorded HOE into the eye: retinal FOV");
  auto a = std::make_shared<TraceArgs>();
  cmd->add_option("SCENE", a->scene, "scene file ('-' or '' = the embedded prototype bench)")->required();
  cmd->add_option("--gaze-deg", a->gazes,
                  "YAW[,PITCH] gaze in degrees (default: the scene's); repeat it for several gazes (JSON list)")
      ->allow_extra_args(false);
  cmd->add_option("--hoe-shift-mm", a->hoe_shift, "X[,Y] lateral HOE shift in its local frame (mm)");
  cmd->add_option("--source-shift-mm", a->source_shift_mm, "projector point-source shift along bench z (mm)");
  cmd->add_option("--wavelength-nm", a->wavelength_nm, "trace only this wavelength (default: all projector lasers)");
  cmd->add_option("--rays", a->rays, "approximate rays per wavelength over the projector FOV (default 4000)");
  cmd->add_option("--threshold", a->threshold, "efficiency threshold for the FOV (default 0.1)");
  cmd->add_option("--polarization", a->polarization, "projector light: s, p or unpolarized (default)");
  cmd->add_flag("--stats", a->stats,
                "add \"stats\":{\"stages_recomputed\":[…],\"evaluations\":N} (memoised stages rerun, Kogelnik solves)");
  cmd->add_flag("--cull", a->cull,
                "skip the coupled-wave step for rays that cannot reach the pupil (mean_efficiency_on_hoe: null)");
  cmd->add_flag("--json", a->json,
                "print {\"fov_deg\":{…},\"rays\",\"rays_in_pupil\",\"rays_efficient\",\"mean_efficiency\",…}");
  cmd->callback([cmd, a] {
    TraceOptions o;
    std::vector<std::optional<std::array<double, 2>>> gazes;
    for (const std::string& text : a->gazes) {
      const auto g = parseNumberList(text, "--gaze-deg", 1, 2);
      gazes.push_back(std::array<double, 2>{g[0], g.size() > 1 ? g[1] : 0.0});
    }
    const bool list = gazes.size() > 1;
    if (gazes.empty()) gazes.push_back(std::nullopt);
    if (!a->hoe_shift.empty()) {
      const auto s = parseNumberList(a->hoe_shift, "--hoe-shift-mm", 1, 2);
      o.hoe_shift_mm = {s[0], s.size() > 1 ? s[1] : 0.0};
    }
    if (!std::isfinite(a->source_shift_mm)) usageError("--source-shift-mm: must be a finite number");
    o.source_shift_mm = a->source_shift_mm;
    if (cmd->count("--wavelength-nm")) {
      if (!(std::isfinite(a->wavelength_nm) && a->wavelength_nm > 0.0))
        usageError("--wavelength-nm: must be a positive number");
      o.wavelength_nm = a->wavelength_nm;
    }
    if (a->rays < 1 || a->rays > 10'000'000) usageError("--rays: must lie in 1 .. 10000000");
    o.rays = a->rays;
    if (!(std::isfinite(a->threshold) && a->threshold >= 0.0 && a->threshold <= 1.0))
      usageError("--threshold: must lie in [0, 1]");
    o.efficiency_threshold = a->threshold;
    const auto pol = parsePolarization(a->polarization);
    if (!pol) usageError("--polarization: unknown polarisation '" + a->polarization + "' (s, p or unpolarized)");
    o.polarization = *pol;

    o.cull_to_pupil = a->cull;

    const Scene scene = loadSceneOrExit(a->scene == "-" ? std::string() : a->scene);
    TracePipeline pipeline;
    nlohmann::json results = nlohmann::json::array();
    for (const auto& gaze : gazes) {
      o.gaze_deg = gaze;
      TraceStats stats;
      const TraceResult r = pipeline.run(scene, o, &stats);
      nlohmann::json out = traceResultJson(r, o);
      if (a->stats) out["stats"] = {{"stages_recomputed", stats.stages_recomputed}, {"evaluations", stats.evaluations}};
      if (!a->json) {
        std::cout << "gaze " << r.gaze_deg[0] << "," << r.gaze_deg[1] << ": FOV " << r.fov_deg.horizontal << " x "
                  << r.fov_deg.vertical << " deg (diagonal " << r.fov_deg.diagonal << "), " << r.rays_efficient
                  << " of " << r.rays << " rays efficient, " << r.rays_in_pupil << " in the pupil, mean efficiency "
                  << r.mean_efficiency;
        if (a->stats)
          std::cout << "; " << stats.stages_recomputed.size() << " stages recomputed, " << stats.evaluations
                    << " coupled-wave evaluations";
        std::cout << "\n";
      }
      results.push_back(std::move(out));
    }
    if (a->json) printJson(list ? results : results[0]);
  });
}

const Registrar reg{"trace", &install};

}  // namespace
}  // namespace fovea::cli
