// fovea-cli blend-profile [--scene SCENE] [--step-deg S] [--no-blend] [--json]
// Seed B.2.3: foveal intensity weight and blur sigma against eccentricity, 0 to 10 deg.
#include <cmath>
#include <iostream>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "model/image/foveation.h"

namespace fovea::cli {
namespace cmd_blend_profile {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("blend-profile", "Foveal weight and blur against eccentricity (B.2.3)");
  struct Args {
    std::string scene;
    double step = 0.25;
    bool noBlend = false, json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--scene", a->scene, "scene file (default: the prototype bench)");
  addCheckedOption(cmd, "--step-deg", a->step,
                   analysis::number("step-deg", "Step", "deg", 0.25, 0.001, 0.25, 3, "eccentricity step"));
  cmd->add_flag("--no-blend", a->noBlend, "profile of the hard switch");
  cmd->add_flag("--json", a->json, "print {\"samples\":[{\"eccentricity_deg\",\"foveal_weight\",\"blur_sigma_deg\"}]}");
  cmd->callback([a] {
    const Scene scene = loadSceneOrExit(a->scene);
    const image::BlendProfile p = image::blendProfile(scene, !a->noBlend);
    const int n = static_cast<int>(std::ceil(10.0 / a->step - 1e-9));
    nlohmann::json samples = nlohmann::json::array();
    for (int i = 0; i <= n; ++i) {
      const double e = std::min(10.0, i * a->step);
      samples.push_back({{"eccentricity_deg", e},
                         {"foveal_weight", p.fovealWeight(e)},
                         {"peripheral_weight", 1.0 - p.fovealWeight(e)},
                         {"blur_sigma_deg", p.blurSigmaDeg(e)}});
    }
    const image::DisplayAngles ang = image::displayAngles(scene);
    nlohmann::json out{{"samples", samples},
                       {"blur_start_deg", p.blur_start_deg},
                       {"blend_start_deg", p.blend_start_deg},
                       {"blend_end_deg", p.blend_end_deg},
                       {"blur_sigma_match_deg", p.sigma_match_deg},
                       {"foveal_cpd", ang.fovealCpd()},
                       {"peripheral_cpd", ang.peripheralCpd()},
                       {"blend", !a->noBlend}};
    if (a->json) {
      printJson(out);
      return;
    }
    for (const auto& s : samples)
      std::cout << s["eccentricity_deg"].get<double>() << "\t" << s["foveal_weight"].get<double>() << "\t"
                << s["blur_sigma_deg"].get<double>() << "\n";
  });
}

const Registrar reg{"blend-profile", &install};

}  // namespace
}  // namespace cmd_blend_profile
}  // namespace fovea::cli
