// fovea-cli gaze-fit --samples FILE [--model poly1|bilinear|poly2] [--average N] [--json]
// Seed C.4: polynomial map from pupil-centre pixels to gaze yaw/pitch (deg), 5 or 9
// targets, 10-sample temporal averaging, accuracy and precision on held-out targets.
// FILE: {"format":"fovea-gaze-samples","version":1,"targets":[{"label":..,
//        "target_deg":[yaw,pitch],"holdout":false,"pupil_px":[[x,y],...]},...]}
#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/preview_json_io.h"
#include "model/gaze/gaze_calibration.h"

namespace fovea::cli {
namespace cmd_gaze_fit {  // one per command file: fovea-cli compiles in unity batches
namespace {

nlohmann::json pair(const std::array<double, 2>& a) {
  return {a[0], a[1]};
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("gaze-fit", "Fit the pupil-to-gaze calibration map (C.4)");
  struct Args {
    std::string samples, model;
    int average = 10;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--samples", a->samples, "JSON samples file (docs/preview.md)")->required();
  cmd->add_option("--model", a->model, "poly1, bilinear or poly2 (default: by the number of targets)")
      ->check(CLI::IsMember({"poly1", "bilinear", "poly2"}));
  cmd->add_option("--average", a->average, "pupil samples averaged per target (default 10)")
      ->check(CLI::Range(1, 100000));
  cmd->add_flag("--json", a->json, "print the result as JSON");
  cmd->callback([a] {
    const nlohmann::json in = readJsonFileOrExit(a->samples);
    gaze::GazeCalibrationOptions o;
    o.average = a->average;
    if (!a->model.empty()) o.model = gaze::modelFromName(a->model);
    gaze::GazeCalibrationResult r;
    try {
      r = gaze::calibrateGaze(gaze::parseGazeSamples(in), o);
    } catch (const std::invalid_argument& e) {
      inputError(a->samples + ": " + e.what());
    }
    const auto& m = r.map;
    nlohmann::json yaw = nlohmann::json::array(), pitch = nlohmann::json::array();
    for (int i = 0; i < m.coefficients.rows(); ++i) {
      yaw.push_back(m.coefficients(i, 0));
      pitch.push_back(m.coefficients(i, 1));
    }
    nlohmann::json targets = nlohmann::json::array();
    for (const auto& v : r.validated)
      targets.push_back({{"label", v.label},
                         {"target_deg", pair(v.target_deg)},
                         {"estimate_deg", pair(v.estimate_deg)},
                         {"error_deg", v.error_deg},
                         {"precision_rms_s2s_deg", v.precision_rms_s2s_deg},
                         {"precision_sd_deg", v.precision_sd_deg},
                         {"samples", v.samples}});
    const nlohmann::json out{
        {"model", gaze::modelName(m.model)},
        {"terms", gaze::termNames(m.model)},
        {"coefficients", {{"yaw_deg", yaw}, {"pitch_deg", pitch}}},
        {"normalisation", {{"centre_px", {m.centre_px[0], m.centre_px[1]}}, {"scale_px", m.scale_px}}},
        {"calibration_targets", r.calibration_targets},
        {"averaged_samples", a->average},
        {"fit_rms_deg", r.fit_rms_deg},
        {"validation", {{"method", r.validation}, {"targets", targets.size()}}},
        {"accuracy_deg", {{"mean", r.accuracy_mean_deg}, {"max", r.accuracy_max_deg}}},
        {"precision_deg", {{"rms_s2s", r.precision_rms_s2s_deg}, {"sd", r.precision_sd_deg}}},
        {"validated_targets", targets}};
    if (a->json) {
      printJson(out);
      return;
    }
    std::cout << gaze::modelName(m.model) << " map from " << r.calibration_targets << " targets; " << r.validation
              << ": accuracy " << r.accuracy_mean_deg << " deg mean (" << r.accuracy_max_deg
              << " max), precision RMS-S2S " << r.precision_rms_s2s_deg << " deg, SD " << r.precision_sd_deg
              << " deg\n";
  });
}

const Registrar reg{"gaze-fit", &install};

}  // namespace
}  // namespace cmd_gaze_fit
}  // namespace fovea::cli
