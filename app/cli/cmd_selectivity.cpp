// fovea-cli selectivity SCENE [--point-mm U,V] [--angle-span-deg A] [--wavelength-span-nm W]
//                       [--samples N] [--polarization s|p|unpolarized] --json
// Angular and spectral selectivity of every recorded HOE layer at one plate point
// (model/analysis/hoe_selectivity.h): efficiency vs probe detuning and vs wavelength, the
// Bragg peak and the full widths at half maximum. The studio's analyses panel runs the same.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/hoe_selectivity.h"

namespace fovea::cli {
namespace {

struct SelectivityArgs {
  std::string scene, point, polarization = "unpolarized";
  double angle_span_deg = 10.0, wavelength_span_nm = 40.0;
  int samples = 401;
  bool json = false;
};

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("selectivity",
                                 "Efficiency vs probe detuning and wavelength of every HOE layer at one plate point");
  auto a = std::make_shared<SelectivityArgs>();
  cmd->add_option("SCENE", a->scene, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--point-mm", a->point, "U[,V] plate point in the HOE's local frame (mm, default 0,0)");
  cmd->add_option("--angle-span-deg", a->angle_span_deg, "detuning range -A..A (deg, default 10)")
      ->check(CLI::Range(0.01, 80.0));
  cmd->add_option("--wavelength-span-nm", a->wavelength_span_nm, "wavelength range around each layer (nm, default 40)")
      ->check(CLI::Range(0.1, 500.0));
  cmd->add_option("--samples", a->samples, "samples per curve (default 401)")->check(CLI::Range(11, 100001));
  cmd->add_option("--polarization", a->polarization, "s, p or unpolarized (default)");
  cmd->add_flag("--json", a->json, "print JSON");
  cmd->callback([a] {
    SelectivityOptions o;
    if (!a->point.empty()) {
      const auto p = parseNumberList(a->point, "--point-mm", 1, 2);
      o.point_mm = {p[0], p.size() > 1 ? p[1] : 0.0};
    }
    o.angle_span_deg = a->angle_span_deg;
    o.wavelength_span_nm = a->wavelength_span_nm;
    o.angle_samples = o.wavelength_samples = a->samples;
    const auto pol = parsePolarization(a->polarization);
    if (!pol) usageError("--polarization: unknown polarisation '" + a->polarization + "' (s, p or unpolarized)");
    o.polarization = *pol;
    const Scene scene = loadSceneOrExit(a->scene);
    if (scene.hoe_layers.empty()) inputError("the scene has no HOE layer");
    const SelectivityResult r = analyzeSelectivity(scene, o);
    if (a->json) return printJson(selectivityResultJson(r));
    std::cout << "layer     probe_nm  incidence_deg  nominal_eff  peak_detuning_deg  angular_fwhm_deg  "
                 "peak_nm  spectral_fwhm_nm\n"
              << std::fixed << std::setprecision(3);
    for (const auto& l : r.layers) {
      std::cout << std::left << std::setw(10) << l.name << std::right << std::setw(8) << l.probe_wavelength_nm
                << std::setw(15) << l.incidence_deg << std::setw(13) << l.nominal_efficiency << std::setw(19)
                << l.peak_detuning_deg << std::setw(18) << l.angular_fwhm_deg.value_or(NAN) << std::setw(9)
                << l.peak_wavelength_nm << std::setw(18) << l.spectral_fwhm_nm.value_or(NAN) << "\n";
    }
  });
}

const Registrar reg{"selectivity", &install};

}  // namespace
}  // namespace fovea::cli
