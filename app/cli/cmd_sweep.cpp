// fovea-cli sweep SCENE --gaze-from A --gaze-to B --gaze-step S [--axis yaw|pitch] --json:
// for each gaze the lateral HOE shift maximising the FOV (supplement A.3), and the eye box.
#include <iomanip>
#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/study_cli.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/gaze_studies.h"

namespace fovea::cli {

GazeAxis parseAxis(const std::string& axis) {
  if (axis == "yaw") return GazeAxis::Yaw;
  if (axis == "pitch") return GazeAxis::Pitch;
  usageError("--axis: expected yaw or pitch, got '" + axis + "'");
}

namespace {

void install(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("sweep", "HOE travel vs gaze: the FOV-maximising HOE shift per gaze angle, and the eye box");
  auto path = std::make_shared<std::string>();
  auto from = std::make_shared<double>(-20.0), to = std::make_shared<double>(20.0),
       step = std::make_shared<double>(5.0);
  auto axis = std::make_shared<std::string>("yaw");
  auto method = std::make_shared<std::string>("hoe");
  auto json = std::make_shared<bool>(false);
  auto opt = std::make_shared<StudyCliOptions>();
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--gaze-from", *from, "first gaze angle (deg)");
  cmd->add_option("--gaze-to", *to, "last gaze angle (deg)");
  cmd->add_option("--gaze-step", *step, "gaze step (deg, > 0)");
  cmd->add_option("--axis", *axis, "yaw (horizontal, HOE x) or pitch (vertical, HOE y)");
  cmd->add_option("--method", *method,
                  "hoe (move the HOE laterally, default) or source (move the projector along bench z)")
      ->check(CLI::IsMember({"hoe", "source"}));
  cmd->add_flag("--json", *json, "print JSON");
  addStudyOptions(cmd, *opt);
  cmd->callback([=] {
    const GazeAxis ax = parseAxis(*axis);
    const ShiftMethod m = *method == "source" ? ShiftMethod::Source : ShiftMethod::Hoe;
    if (!(*step > 0) || !std::isfinite(*step)) usageError("--gaze-step: must be > 0");
    if (!(*to >= *from)) usageError("--gaze-to: must be >= --gaze-from");
    if ((*to - *from) / *step > 2000) usageError("--gaze-step: more than 2000 gaze samples");
    const Scene scene = loadSceneOrExit(*path);
    const nlohmann::json params{{"from", *from}, {"to", *to}, {"step", *step}, {"axis", *axis}, {"method", *method}};
    const nlohmann::json out = cachedStudy("sweep", params, scene, *opt, [&] {
      const FovEvaluator eval = studyEvaluator(*opt);
      Progress progress("sweep");
      StudyControl control;
      control.on_progress = [&progress](double f) { progress.update(f); };
      GazeStudyOptions g;
      g.tolerance_deg = opt->tolerance_deg;
      const auto r = sweepGaze(scene, eval, *from, *to, *step, ax, m, g, control);
      if (!r.ok()) inputError("sweep did not complete");
      return sweepResultJson(*r.value, *axis);  // the same document as the studio's
    });
    if (*json) {
      printJson(out);
      return;
    }
    std::cout << "gaze_deg      shift_mm  fov_h  fov_v  fov_d\n" << std::fixed << std::setprecision(2);
    for (const auto& s : out["samples"])
      std::cout << std::setw(8) << s["gaze_deg"].get<double>() << std::setw(14)
                << (s["hoe_shift_mm"].get<double>() + s["source_shift_mm"].get<double>()) << std::setw(7)
                << s["fov_deg"]["horizontal"].get<double>() << std::setw(7) << s["fov_deg"]["vertical"].get<double>()
                << std::setw(7) << s["fov_deg"]["diagonal"].get<double>() << "\n";
    std::cout << "eye box " << out["eyebox_mm"].get<double>() << " mm\n";
  });
}

const Registrar reg{"sweep", &install};

}  // namespace
}  // namespace fovea::cli
