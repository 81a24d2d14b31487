// fovea-cli selectivity SCENE [--point-mm U,V] [--angle-span-deg A] [--wavelength-span-nm W]
//                       [--samples N] [--polarization s|p|unpolarized] --json
// Angular and spectral selectivity of every recorded HOE layer at one plate point
// (model/analysis/hoe_selectivity.h): efficiency vs probe detuning and vs wavelength, the
// Bragg peak and the full widths at half maximum. Options: the "selectivity" analysis of the
// registry (model/analysis/study_analyses.cpp), which the studio's analyses panel runs too;
// --eye left|right|both: each eye of a binocular scene (app/cli/eye_option.h).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "app/cli/study_cli.h"
#include "model/analysis/hoe_selectivity.h"
#include "model/analysis/study_analyses.h"

namespace fovea::cli {
namespace cmd_selectivity {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("selectivity",
                                 "Efficiency vs probe detuning and wavelength of every HOE layer at one plate point");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *path, "scene file (default: the embedded prototype bench)");
  const auto options = addAnalysisOptions(cmd, "selectivity");
  cmd->add_flag("--json", *json, "print JSON");
  const auto eye = addEyeOption(cmd);
  cmd->callback([path, options, json, eye] {
    const nlohmann::json values = options->values();
    const std::vector<EyeRun> runs = eyeRuns(loadSceneOrExit(*path), *eye, *path);
    if (*json) {
      std::vector<nlohmann::json> docs;
      for (const EyeRun& run : runs) docs.push_back(runStudy(options->definition(), run.scene, values));
      return printJson(combineEyeDocuments(runs, docs));
    }
    for (const EyeRun& run : runs) {
      const Scene& scene = run.scene;
      if (scene.hoe_layers.empty()) inputError("the scene has no HOE layer");
      const SelectivityResult r = analyzeSelectivity(scene, analysis::selectivityOptionsFrom(values));
      if (run.side) std::cout << eyePrefix(run) << "\n";
      std::cout << "layer     probe_nm  incidence_deg  nominal_eff  peak_detuning_deg  angular_fwhm_deg  "
                   "peak_nm  spectral_fwhm_nm\n"
                << std::fixed << std::setprecision(3);
      for (const auto& l : r.layers) {
        std::cout << std::left << std::setw(10) << l.name << std::right << std::setw(8) << l.probe_wavelength_nm
                  << std::setw(15) << l.incidence_deg << std::setw(13) << l.nominal_efficiency << std::setw(19)
                  << l.peak_detuning_deg << std::setw(18) << l.angular_fwhm_deg.value_or(NAN) << std::setw(9)
                  << l.peak_wavelength_nm << std::setw(18) << l.spectral_fwhm_nm.value_or(NAN) << "\n";
      }
    }
  });
}

const Registrar reg{"selectivity", &install};

}  // namespace
}  // namespace cmd_selectivity
}  // namespace fovea::cli
