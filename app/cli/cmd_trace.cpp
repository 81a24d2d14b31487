// fovea-cli trace SCENE: projector -> recorded HOE stack -> eye; retinal FOV (contract: docs/physics.md).
// --gaze-deg may repeat: one memoised pipeline (model/physics/trace_pipeline.h) serves every
// gaze and the output is a JSON list, one result per gaze; --stats adds
// "stats":{"stages_recomputed":[...],"evaluations":N} to each result. Options: the "trace"
// analysis of the registry (model/analysis/study_analyses.cpp) plus --stats, --cull and --eye
// (app/cli/eye_option.h: each eye of a binocular scene, its own pipeline).
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/study_analyses.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"

namespace fovea::cli {
namespace cmd_trace {  // one per command file: fovea-cli compiles in unity batches
namespace {

struct TraceArgs {
  std::string scene;
  bool json = false, stats = false, cull = false;
};

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("trace", "Trace the projector through the recorded HOE into the eye: retinal FOV");
  auto a = std::make_shared<TraceArgs>();
  cmd->add_option("SCENE", a->scene, "scene file ('-' or '' = the embedded prototype bench)")->required();
  const auto options = addAnalysisOptions(cmd, "trace");
  cmd->add_flag("--stats", a->stats,
                "add \"stats\":{\"stages_recomputed\":[…],\"evaluations\":N} (memoised stages rerun, Kogelnik solves)");
  cmd->add_flag("--cull", a->cull,
                "skip the coupled-wave step for rays that cannot reach the pupil (mean_efficiency_on_hoe: null)");
  cmd->add_flag("--json", a->json,
                "print {\"fov_deg\":{…},\"rays\",\"rays_in_pupil\",\"rays_efficient\",\"mean_efficiency\",…}");
  const auto eye = addEyeOption(cmd);
  cmd->callback([a, options, eye] {
    // One value set per --gaze-deg (the scene's gaze when none is given).
    const std::vector<nlohmann::json> per_gaze = options->valuesPerOccurrence("gaze-deg");
    const bool list = per_gaze.size() > 1;
    const Scene loaded = loadSceneOrExit(a->scene == "-" ? std::string() : a->scene);
    const std::vector<EyeRun> runs = eyeRuns(loaded, *eye, a->scene == "-" ? std::string() : a->scene);
    // docs[gaze][run]: each eye's usual result per gaze, combined per gaze (eye_option.h).
    std::vector<std::vector<nlohmann::json>> docs(per_gaze.size());
    for (const EyeRun& run : runs) {
      const Scene& scene = run.scene;
      TracePipeline pipeline;
      for (std::size_t g = 0; g < per_gaze.size(); ++g) {
        const nlohmann::json& values = per_gaze[g];
        TraceOptions o = analysis::traceOptionsFrom(values);
        o.cull_to_pupil = a->cull;
        TraceStats stats;
        const TraceResult r = pipeline.run(scene, o, &stats);
        const TraceFov fov = traceFov(scene, r, o);
        const FovMethod method = analysis::traceFovMethodFrom(values);
        nlohmann::json out = traceResultJson(r, o, fov, method);
        if (a->stats)
          out["stats"] = {{"stages_recomputed", stats.stages_recomputed}, {"evaluations", stats.evaluations}};
        if (!a->json) {
          const FovDeg f = fov.shown(method);
          std::cout << eyePrefix(run) << "gaze " << r.gaze_deg[0] << "," << r.gaze_deg[1] << ": FOV ("
                    << fovMethodName(method) << ") " << f.horizontal << " x " << f.vertical << " deg (diagonal "
                    << f.diagonal << "), " << r.rays_efficient << " of " << r.rays << " rays efficient, "
                    << r.rays_in_pupil << " in the pupil, mean efficiency " << r.mean_efficiency;
          if (a->stats)
            std::cout << "; " << stats.stages_recomputed.size() << " stages recomputed, " << stats.evaluations
                      << " coupled-wave evaluations";
          std::cout << "\n";
        }
        docs[g].push_back(std::move(out));
      }
    }
    nlohmann::json results = nlohmann::json::array();
    for (const auto& per_eye : docs) results.push_back(combineEyeDocuments(runs, per_eye));
    if (a->json) printJson(list ? results : results[0]);
  });
}

const Registrar reg{"trace", &install};

}  // namespace
}  // namespace cmd_trace
}  // namespace fovea::cli
