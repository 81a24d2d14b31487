// fovea-cli resolution SCENE [--gaze-deg A[,B]] [--accommodation-d D,...] --json: angular
// resolution vs eccentricity (supplement A.5). foveal_cpd / optical_limit_cpd are null outside
// the micro-OLED field. --accommodation-d adds "accommodation": the peripheral and foveal
// retinal spot and cpd (MTF50, MTF10) at the line of sight for each accommodation (issue 29,
// model/analysis/accommodation_resolution.h); null without the flag.
// Options: the "resolution" analysis of the registry (model/analysis/study_analyses.cpp).
#include <iomanip>
#include <iostream>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "app/cli/study_cli.h"
#include "model/analysis/accommodation_resolution.h"
#include "model/analysis/angular_resolution.h"
#include "model/analysis/study_analyses.h"

namespace fovea::cli {
namespace cmd_resolution {  // one per command file: fovea-cli compiles in unity batches
namespace {

// The text table of one scene (the model's result itself, not its JSON document).
void printTable(const Scene& scene, const nlohmann::json& values) {
  ResolutionOptions opt;
  opt.samples = analysis::integerOf(values, "samples");
  opt.gaze_deg = analysis::gazeFrom(values);
  const ResolutionResult r = analyzeResolution(scene, opt);
  if (r.samples.empty()) inputError("no line of sight reaches the HOE or the foveal image for this gaze");
  std::cout << "gaze " << r.gaze_yaw_deg << "," << r.gaze_pitch_deg << " deg; peripheral field "
            << r.peripheral_field_deg[0] << ".." << r.peripheral_field_deg[1] << " deg; pixel integral "
            << r.peripheral_pixel_integral << " of " << r.pixels_horizontal << " (" << r.peripheral_pixels_on_hoe
            << " land on the HOE)\n";
  std::cout << "ecc_deg  foveal  peripheral  optical  perceived (cpd)\n" << std::fixed << std::setprecision(2);
  const std::size_t stride = std::max<std::size_t>(1, r.samples.size() / 30);
  for (std::size_t i = 0; i < r.samples.size(); i += stride) {
    const auto& s = r.samples[i];
    std::cout << std::setw(7) << s.eccentricity_deg << std::setw(8) << s.foveal_cpd.value_or(0) << std::setw(12)
              << s.peripheral_cpd.value_or(0) << std::setw(9) << s.optical_limit_cpd.value_or(0) << std::setw(11)
              << s.perceived_cpd << "\n";
  }
  if (values.contains("accommodation-d") && !values["accommodation-d"].is_null()) {
    const AccommodationList list = parseAccommodationList(analysis::textOf(values, "accommodation-d"));
    const AccommodationResolution a =
        resolutionVsAccommodation(scene, {r.gaze_yaw_deg, r.gaze_pitch_deg}, list.values_d);
    std::cout << "accommodation_d  peripheral MTF50 MTF10  foveal MTF50 MTF10 (cpd)\n";
    for (const auto& s : a.samples) {
      if (a.peripheral_reference >= s.peripheral.size() || a.foveal_reference >= s.foveal.size()) continue;
      const auto& p = s.peripheral.at(a.peripheral_reference);
      const auto& f = s.foveal.at(a.foveal_reference);
      std::cout << std::setw(15) << s.accommodation_d << std::setw(18) << (p.valid ? p.metrics.mtf50_cpd : 0.0)
                << std::setw(6) << (p.valid ? p.metrics.mtf10_cpd : 0.0) << std::setw(14) << f.metrics.mtf50_cpd
                << std::setw(6) << f.metrics.mtf10_cpd << "\n";
    }
  }
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "resolution",
      "Angular resolution (cpd) vs eccentricity for a gaze: foveal, peripheral, optical limit, perceived");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  const auto options = addAnalysisOptions(cmd, "resolution");
  cmd->add_flag("--json", *json, "print JSON");
  const auto eye = addEyeOption(cmd);
  cmd->callback([path, options, json, eye] {
    const nlohmann::json values = options->values();
    const std::vector<EyeRun> runs = eyeRuns(loadSceneOrExit(*path), *eye, *path);
    if (*json) {
      std::vector<nlohmann::json> docs;
      for (const EyeRun& run : runs) docs.push_back(runStudy(options->definition(), run.scene, values));
      printJson(combineEyeDocuments(runs, docs));
      return;
    }
    for (const EyeRun& run : runs) {
      if (run.side) std::cout << eyePrefix(run) << "\n";
      printTable(run.scene, values);
    }
  });
}

const Registrar reg{"resolution", &install};

}  // namespace
}  // namespace cmd_resolution
}  // namespace fovea::cli
