// fovea-cli color-map CAL.json --display foveal|peripheral --rgb R,G,B [--json]
// Drive values (real, on the display's own 0..255 code scale) for one target RGB.
#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/preview_json_io.h"
#include "model/color/color_calibration.h"

namespace fovea::cli {
namespace cmd_color_map {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("color-map", "Drive values of one display for a target RGB (B.2.2)");
  struct Args {
    std::string cal, display, rgb;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("CAL", a->cal, "calibration file written by color-calibrate")->required();
  cmd->add_option("--display", a->display, "foveal or peripheral")
      ->required()
      ->check(CLI::IsMember({"foveal", "peripheral"}));
  cmd->add_option("--rgb", a->rgb, "target R,G,B in 0..255")->required();
  cmd->add_flag("--json", a->json, "print {\"drive\":[r,g,b]}");
  cmd->callback([a] {
    const auto v = parseNumberList(a->rgb, "--rgb", 3, 3);
    for (double c : v)
      if (!(c >= 0 && c <= 255)) usageError("--rgb values must lie in 0..255");
    color::ColorCalibration cal;
    try {
      cal = color::calibrationFromJson(readJsonFileOrExit(a->cal));
    } catch (const std::invalid_argument& e) {
      inputError(a->cal + ": " + e.what());
    }
    const auto d = a->display == "foveal" ? color::Display::Foveal : color::Display::Peripheral;
    const Eigen::Vector3d rgb(v[0], v[1], v[2]);
    const Eigen::Vector3d drive = cal.drive(d, rgb);
    const Eigen::Vector3d xyz = cal.targetXyz(rgb);
    if (a->json) {
      printJson({{"drive", {drive[0], drive[1], drive[2]}},
                 {"display", a->display},
                 {"target_xyz", {xyz[0], xyz[1], xyz[2]}},
                 {"drive_rounded", {std::round(drive[0]), std::round(drive[1]), std::round(drive[2])}}});
      return;
    }
    std::cout << drive[0] << " " << drive[1] << " " << drive[2] << "\n";
  });
}

const Registrar reg{"color-map", &install};

}  // namespace
}  // namespace cmd_color_map
}  // namespace fovea::cli
