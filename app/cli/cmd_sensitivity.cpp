// fovea-cli sensitivity SCENE --parameter PATH --from A --to B --steps N --json: FOV, mean
// efficiency and efficiency uniformity over values of any numeric scene parameter (a JSON
// path into the scene file, e.g. eye.relief_mm, hoe_layers[1].shrinkage_percent).
#include <iomanip>
#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/study_cli.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/gaze_studies.h"

namespace fovea::cli {

namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("sensitivity", "FOV and efficiency over values of one scene parameter (JSON path)");
  auto path = std::make_shared<std::string>();
  auto parameter = std::make_shared<std::string>();
  auto from = std::make_shared<double>(0.0), to = std::make_shared<double>(0.0);
  auto steps = std::make_shared<int>(5);
  auto json = std::make_shared<bool>(false);
  auto opt = std::make_shared<StudyCliOptions>();
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--parameter", *parameter, "JSON path of a number in the scene file, e.g. eye.relief_mm")->required();
  cmd->add_option("--from", *from, "first value")->required();
  cmd->add_option("--to", *to, "last value")->required();
  cmd->add_option("--steps", *steps, "number of values (>= 1)")->check(CLI::Range(1, 10000));
  cmd->add_flag("--json", *json, "print JSON");
  addStudyOptions(cmd, *opt);
  cmd->callback([=] {
    if (!std::isfinite(*from) || !std::isfinite(*to)) usageError("--from/--to: must be finite numbers");
    const Scene scene = loadSceneOrExit(*path);
    double nominal = 0;
    try {
      nominal = parameterValue(scene, *parameter);
      withParameter(scene, *parameter, *from);
      withParameter(scene, *parameter, *to);
    } catch (const std::invalid_argument& e) {
      usageError(std::string("--parameter: ") + e.what());
    }
    const nlohmann::json params{{"parameter", *parameter}, {"from", *from}, {"to", *to}, {"steps", *steps}};
    const nlohmann::json out = cachedStudy("sensitivity", params, scene, *opt, [&] {
      const FovEvaluator eval = studyEvaluator(*opt);
      Progress progress("sensitivity");
      StudyControl control;
      control.on_progress = [&progress](double f) { progress.update(f); };
      StudyOutcome<std::vector<SensitivitySample>> r;
      try {
        r = sensitivitySweep(scene, eval, *parameter, *from, *to, *steps, control);
      } catch (const std::invalid_argument& e) {
        inputError(std::string("--parameter: ") + e.what());
      }
      if (!r.ok()) inputError("sensitivity sweep did not complete");
      return sensitivityResultJson(*r.value, *parameter, nominal);  // the same document as the studio's
    });
    if (*json) {
      printJson(out);
      return;
    }
    std::cout << *parameter << "  fov_h  fov_v  mean_eff  uniformity\n" << std::fixed << std::setprecision(3);
    for (const auto& s : out["samples"])
      std::cout << s["value"].get<double>() << "  " << s["fov_deg"]["horizontal"].get<double>() << "  "
                << s["fov_deg"]["vertical"].get<double>() << "  " << s["mean_efficiency"].get<double>() << "  "
                << s["efficiency_uniformity"].get<double>() << "\n";
  });
}

const Registrar reg{"sensitivity", &install};

}  // namespace
}  // namespace fovea::cli
