// fovea-cli composite --image IN [--scene SCENE] --gaze-deg YAW,PITCH [--no-blend]
//                     --out-foveal F --out-peripheral P --out-perceived Q [--json]
//                     [--warp-foveal PAIRS] [--warp-peripheral PAIRS] [--warp-model M]
// Seed B.2.3: the micro-OLED image, the projector image and the perceived composite for one
// gaze, with the seam visibility (LDR-FLIP over the transition annulus).
#include <chrono>
#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/preview_json_io.h"
#include "model/image/foveation.h"
#include "model/image/image_io.h"

namespace fovea::cli {
namespace cmd_composite {  // one per command file: fovea-cli compiles in unity batches
namespace {

// A display's geometric pre-warp from a fit-warp pairs file: src = physical display pixel,
// dst = the ideal (equal-angle) display pixel whose content it must show.
image::GazeWarpGrid warpFromPairs(const std::string& path, image::WarpModel model) {
  const nlohmann::json in = readJsonFileOrExit(path);
  if (!in.is_object() || !in.contains("pairs") || !in["pairs"].is_array())
    inputError(path + ": needs a \"pairs\" array of {\"src\":[x,y],\"dst\":[u,v]}");
  std::vector<image::PointPair> pairs;
  for (std::size_t i = 0; i < in["pairs"].size(); ++i) {
    const auto& p = in["pairs"][i];
    auto pt = [&](const char* key) {
      if (!p.is_object() || !p.contains(key) || !p[key].is_array() || p[key].size() != 2 || !p[key][0].is_number() ||
          !p[key][1].is_number())
        inputError(path + ": pairs[" + std::to_string(i) + "]." + key + " must be [x, y] numbers");
      return Eigen::Vector2d(p[key][0].get<double>(), p[key][1].get<double>());
    };
    pairs.push_back({pt("src"), pt("dst")});
  }
  try {
    return image::GazeWarpGrid({0.0}, {0.0}, {image::fitWarp(pairs, model)});
  } catch (const image::WarpError& e) {
    inputError(path + ": " + e.what());
  }
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("composite", "Foveal, peripheral and perceived images for one gaze (B.2.3)");
  struct Args {
    std::string image, scene, gaze, foveal, peripheral, perceived, warpFoveal, warpPeripheral, warpModel = "poly2";
    bool noBlend = false, json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--image", a->image, "target image covering the peripheral FOV")->required();
  cmd->add_option("--scene", a->scene, "scene file (default: the prototype bench)");
  cmd->add_option("--gaze-deg", a->gaze, "gaze yaw,pitch in degrees")->required();
  cmd->add_flag("--no-blend", a->noBlend, "hard switch at eps_o, no blur (for comparison)");
  auto* out_foveal = cmd->add_option("--out-foveal", a->foveal, "micro-OLED image to write")->required();
  auto* out_peripheral = cmd->add_option("--out-peripheral", a->peripheral, "projector image to write")->required();
  auto* out_perceived =
      cmd->add_option("--out-perceived", a->perceived, "perceived composite to write (target grid)")->required();
  cmd->add_flag("--json", a->json, "print {\"seam_metric\":..., \"timings_ms\":{...}}");
  cmd->add_option("--warp-foveal", a->warpFoveal,
                  "pre-warp of the micro-OLED: fit-warp pairs file, src = display pixel, dst = ideal pixel");
  cmd->add_option("--warp-peripheral", a->warpPeripheral, "pre-warp of the projector (same format)");
  cmd->add_option("--warp-model", a->warpModel, "model of the pre-warps: poly1, poly2 (default), poly3, homography")
      ->check(CLI::IsMember({"poly1", "poly2", "poly3", "homography"}));
  cmd->callback([a, out_foveal, out_peripheral, out_perceived] {
    // Before any work: each output a file of its own (the same path twice kept only the last image).
    checkOutputOption(out_foveal, a->foveal);
    checkOutputOption(out_peripheral, a->peripheral);
    checkOutputOption(out_perceived, a->perceived);
    checkDistinctOutputs(
        {{"--out-foveal", a->foveal}, {"--out-peripheral", a->peripheral}, {"--out-perceived", a->perceived}});
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
    image::GazeWarpTables warps;
    const image::WarpModel wm = *image::warpModelFromString(a->warpModel);
    if (!a->warpFoveal.empty()) warps.G_f = warpFromPairs(a->warpFoveal, wm);
    if (!a->warpPeripheral.empty()) warps.G_p = warpFromPairs(a->warpPeripheral, wm);
    image::FoveatedCompositor comp(scene, !a->noBlend, warps);
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
                       {"prewarp", {{"foveal", !a->warpFoveal.empty()}, {"peripheral", !a->warpPeripheral.empty()}}},
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
}  // namespace cmd_composite
}  // namespace fovea::cli
