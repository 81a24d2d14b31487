// fovea-cli compare-shift SCENE --json: HOE shift vs point-source shift (supplement A.4):
// gaze range covered, travel needed and eye box of each method under the same conditions.
#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/study_cli.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/gaze_studies.h"

namespace fovea::cli {

GazeAxis parseAxis(const std::string& axis);

namespace {

void install(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("compare-shift", "Dynamic eye box: moving the HOE vs moving the projector point source");
  auto path = std::make_shared<std::string>();
  auto from = std::make_shared<double>(-40.0), to = std::make_shared<double>(40.0),
       step = std::make_shared<double>(5.0);
  auto axis = std::make_shared<std::string>("yaw");
  auto json = std::make_shared<bool>(false);
  auto opt = std::make_shared<StudyCliOptions>();
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--gaze-from", *from, "gaze range studied, first angle (deg, default -40)");
  cmd->add_option("--gaze-to", *to, "last angle (deg, default 40)");
  cmd->add_option("--gaze-step", *step, "coarse step before the borders are bisected (deg, default 5)");
  cmd->add_option("--axis", *axis, "yaw or pitch");
  cmd->add_flag("--json", *json, "print JSON");
  addStudyOptions(cmd, *opt);
  cmd->callback([=] {
    const GazeAxis ax = parseAxis(*axis);
    if (!(*step > 0) || !(*to >= *from)) usageError("--gaze-step must be > 0 and --gaze-to >= --gaze-from");
    const Scene scene = loadSceneOrExit(*path);
    const nlohmann::json params{{"from", *from}, {"to", *to}, {"step", *step}, {"axis", *axis}};
    const nlohmann::json out = cachedStudy("compare-shift", params, scene, *opt, [&] {
      const FovEvaluator eval = studyEvaluator(*opt);
      Progress progress("compare-shift");
      GazeStudyOptions g;
      g.tolerance_deg = opt->tolerance_deg;
      EyeBox boxes[3];  // hoe, source, static
      int done = 0;
      for (ShiftMethod m : {ShiftMethod::Hoe, ShiftMethod::Source, ShiftMethod::None}) {
        StudyControl control;
        control.on_progress = [&progress, done](double f) { progress.update((done + f) / 3.0); };
        const auto r = sweepGaze(scene, eval, *from, *to, *step, ax, m, g, control);
        if (!r.ok()) inputError("compare-shift did not complete");
        boxes[done++] = r.value->eyebox;
      }
      return compareShiftJson(boxes[0], boxes[1], &boxes[2], ax);  // the same document as the studio's
    });
    if (*json) {
      printJson(out);
      return;
    }
    for (const char* k : {"hoe_shift", "source_shift"}) {
      const auto& e = out[k];
      std::cout << k << ": gaze " << e["gaze_range_deg"][0] << " .. " << e["gaze_range_deg"][1] << " deg, travel "
                << e["travel_mm"][0] << " .. " << e["travel_mm"][1] << " mm, eye box " << e["eyebox_mm"] << " mm\n";
    }
  });
}

const Registrar reg{"compare-shift", &install};

}  // namespace
}  // namespace fovea::cli
