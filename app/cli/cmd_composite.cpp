// fovea-cli composite --image IN [--scene SCENE] --gaze-deg YAW,PITCH [--no-blend]
//                     --out-foveal F --out-peripheral P --out-perceived Q [--json]
// Seed B.2.3: the micro-OLED image, the projector image and the perceived composite for one
// gaze, with the seam visibility (LDR-FLIP over the transition annulus).
#include <chrono>
#include <iostream>

#include "app/cli/cli_common.h"
#include "model/image/foveation.h"
#include "model/image/image_io.h"

namespace fovea::cli {
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("composite", "Foveal, peripheral and perceived images for one gaze (B.2.3)");
  struct Args {
    std::string image, scene, gaze, foveal, peripheral, perceived;
    bool noBlend = false, json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--image", a->image, "target image covering the peripheral FOV")->required();
  cmd->add_option("--scene", a->scene, "scene file (default: the prototype bench)");
  cmd->add_option("--gaze-deg", a->gaze, "gaze yaw,pitch in degrees")->required();
  cmd->add_flag("--no-blend", a->noBlend, "hard switch at eps_o, no blur (for comparison)");
  cmd->add_option("--out-foveal", a->foveal, "micro-OLED image to write")->required();
  cmd->add_option("--out-peripheral", a->peripheral, "projector image to write")->required();
  cmd->add_option("--out-perceived", a->perceived, "perceived composite to write (target grid)")->required();
  cmd->add_flag("--json", a->json, "print {\"seam_metric\":..., \"timings_ms\":{...}}");
  cmd->callback([a] {
    const auto g = parseNumberList(a->gaze, "--gaze-deg", 2, 2);
    const Scene scene = loadSceneOrExit(a->scene);
    const auto t0 = std::chrono::steady_clock::now();
    cv::Mat target;
    try {
      target = image::readLinearRgb(a->image);
    } catch (const image::ImageIoError& e) {
      inputError(e.what());
    }
    const auto t1 = std::chrono::steady_clock::now();
    image::FoveatedCompositor comp(scene, !a->noBlend);
    comp.setTarget(target);
    const auto t2 = std::chrono::steady_clock::now();
    comp.update({g[0], g[1]});
    const auto t3 = std::chrono::steady_clock::now();
    const auto seam = comp.seamMetric();
    const auto t4 = std::chrono::steady_clock::now();
    try {
      image::writeLinearRgb(a->foveal, comp.fovealImage());
      image::writeLinearRgb(a->peripheral, comp.peripheralImage());
      image::writeLinearRgb(a->perceived, comp.perceivedImage());
    } catch (const image::ImageIoError& e) {
      inputError(e.what());
    }
    auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
    const auto& t = comp.timings();
    const auto& p = comp.profile();
    const auto& ang = comp.angles();
    nlohmann::json out{{"seam_metric", seam.mean_flip},
                       {"seam",
                        {{"metric", "LDR-FLIP (Andersson et al. 2020), mean over the transition annulus"},
                         {"annulus_deg", {p.blur_start_deg, p.blend_end_deg}},
                         {"mean", seam.mean_flip},
                         {"p95", seam.p95_flip},
                         {"max", seam.max_flip},
                         {"pixels", seam.pixels},
                         {"pixels_per_degree", comp.targetPpd()}}},
                       {"timings_ms",
                        {{"read", ms(t1 - t0)},
                         {"prepare_target", ms(t2 - t1)},
                         {"gaze_update", t.total_ms},
                         {"foveal", t.foveal_ms},
                         {"peripheral", t.peripheral_ms},
                         {"perceived", t.perceived_ms},
                         {"prewarp", t.prewarp_ms},
                         {"seam_metric", ms(t4 - t3)}}},
                       {"gaze_deg", {g[0], g[1]}},
                       {"blend", !a->noBlend},
                       {"blur_sigma_match_deg", p.sigma_match_deg},
                       {"foveal_cpd", ang.fovealCpd()},
                       {"peripheral_cpd", ang.peripheralCpd()},
                       {"foveal_fov_deg", {ang.foveal_fov_deg[0], ang.foveal_fov_deg[1]}},
                       {"sizes",
                        {{"target", {target.cols, target.rows}},
                         {"foveal", {comp.fovealImage().cols, comp.fovealImage().rows}},
                         {"peripheral", {comp.peripheralImage().cols, comp.peripheralImage().rows}}}}};
    if (a->json) {
      printJson(out);
      return;
    }
    std::cout << "seam (mean FLIP over " << p.blur_start_deg << "-" << p.blend_end_deg << " deg): " << seam.mean_flip
              << "; gaze update " << t.total_ms << " ms\n";
  });
}

const Registrar reg{"composite", &install};

}  // namespace
}  // namespace fovea::cli
