// fovea-cli color-calibrate (MEAS.json | --measurements READINGS.csv) --out CAL.json
//                           [--white-xy x,y] [--gamma G] [--json]
// READINGS.csv: spectroradiometer readings (display,channel,level,x,y,Y,repeat or X,Y,Z), averaged
// per level (model/color/measurement_csv.h); bad rows are reported by line (exit 1).
// Seed B.2.2: common primaries of the foveal and peripheral displays, white balance and the
// look-up tables; writes the calibration file used by `color-map`.
#include <fstream>
#include <iostream>
#include <sstream>

#include "app/cli/cli_common.h"
#include "app/cli/preview_json_io.h"
#include "model/color/color_calibration.h"
#include "model/color/measurement_csv.h"
#include "model/io/json_input.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace cmd_color_calibrate {  // one per command file: fovea-cli compiles in unity batches
namespace {

nlohmann::json xyJson(color::Xy p) {
  return nlohmann::json::array({p.x, p.y});
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("color-calibrate", "Colour-match the foveal and peripheral displays (B.2.2)");
  struct Args {
    std::string meas, csv, out, white;
    double gamma = 2.2;
    int grid = 9;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* meas = cmd->add_option("MEAS", a->meas, "colour measurements (fovea-color-measurements JSON)");
  cmd->add_option("--measurements", a->csv,
                  "spectroradiometer readings CSV (display,channel,level,x,y,Y,repeat) instead of MEAS")
      ->excludes(meas);
  auto* out_option = cmd->add_option("--out", a->out, "calibration file to write")->required();
  cmd->add_option("--white-xy", a->white, "white point chromaticity x,y (default D65 0.3127,0.3290)");
  cmd->add_option("--gamma", a->gamma, "gamma of the calibrated display (default 2.2)");
  cmd->add_option("--report-grid", a->grid, "targets per channel of the dE00 report grid (default 9)")
      ->check(CLI::Range(2, 64));
  cmd->add_flag("--json", a->json, "print the result as JSON");
  cmd->callback([a, out_option] {
    checkOutputOption(out_option, a->out);
    color::ColorCalibrationOptions o;
    if (!a->white.empty()) {
      const auto w = parseNumberList(a->white, "--white-xy", 2, 2);
      o.white = color::Xy{w[0], w[1]};
    }
    if (!(a->gamma > 0 && a->gamma < 10)) usageError("--gamma must lie in (0, 10)");
    o.gamma = a->gamma;
    if (a->meas.empty() == a->csv.empty()) usageError("give exactly one of MEAS.json or --measurements FILE.csv");
    color::ColorCalibration cal;
    nlohmann::json imported;
    const std::string source = a->csv.empty() ? a->meas : a->csv;
    try {
      color::ColorMeasurements m;
      if (!a->csv.empty()) {
        auto text = readInputFile(a->csv, color::kMaxMeasurementCsvBytes);  // regular file, <= 64 MiB
        if (text.index() == 1) inputError(a->csv + ": cannot read the measurements: " + std::get<1>(text));
        const color::MeasurementImport imp = color::importSpectroradiometerCsv(std::get<0>(text));
        if (!imp.ok())
          inputError(std::to_string(imp.problems.size()) + " problem(s) in the measurements, nothing calibrated:\n" +
                     color::formatProblems(imp, a->csv));
        m = imp.measurements;
        imported = {{"file", a->csv},
                    {"readings", imp.rows},
                    {"values", imp.tristimulus ? "tristimulus X,Y,Z" : "chromaticity x,y and luminance Y"},
                    {"repeats_min", imp.min_repeats},
                    {"repeats_max", imp.max_repeats}};
      } else {
        m = color::parseColorMeasurements(readJsonFileOrExit(a->meas));
      }
      cal = color::calibrateColor(m, o);
    } catch (const std::invalid_argument& e) {
      inputError(source + ": " + e.what());
    }
    try {
      writeFileAtomic(a->out, color::toJson(cal).dump(2) + "\n");
    } catch (const std::exception& e) {
      inputError(a->out + ": cannot write the calibration: " + e.what());
    }
    const color::DeltaEReport r = color::deltaEBetweenDisplays(cal, a->grid);
    nlohmann::json common = nlohmann::json::object(), fitted = nlohmann::json::object();
    const char* names[3] = {"R", "G", "B"};
    for (int k = 0; k < 3; ++k) {
      common[names[k]] = xyJson(cal.common[k]);
      fitted["foveal"][names[k]] = color::fitGamma(cal.foveal.curves[k]);
      fitted["peripheral"][names[k]] = color::fitGamma(cal.peripheral.curves[k]);
    }
    nlohmann::json overlap = nlohmann::json::array();
    for (const auto& p : cal.overlap) overlap.push_back(xyJson(p));
    nlohmann::json out{{"common_primaries_xy", common},
                       {"white_xy", xyJson(cal.white)},
                       {"gamma", cal.gamma},
                       {"max_luminance", cal.max_luminance},
                       {"kappa", {cal.kappa[0], cal.kappa[1], cal.kappa[2]}},
                       {"overlap_polygon_xy", overlap},
                       {"overlap_area", color::signedArea(cal.overlap)},
                       {"common_area", color::triangleArea(cal.common)},
                       {"measured_gamma", fitted},
                       {"delta_e00",
                        {{"targets", r.targets},
                         {"mean", r.mean},
                         {"p95", r.p95},
                         {"max", r.max},
                         {"worst_rgb", {r.worst_rgb[0], r.worst_rgb[1], r.worst_rgb[2]}},
                         {"mean_unquantised", r.mean_real_drive},
                         {"max_unquantised", r.max_real_drive}}},
                       {"calibration_file", a->out}};
    if (!imported.is_null()) out["measurements_csv"] = imported;
    if (a->json) {
      printJson(out);
      return;
    }
    std::cout << "common primaries R (" << cal.common[0].x << ", " << cal.common[0].y << ") G (" << cal.common[1].x
              << ", " << cal.common[1].y << ") B (" << cal.common[2].x << ", " << cal.common[2].y << ")\n"
              << "white (" << cal.white.x << ", " << cal.white.y << "), gamma " << cal.gamma << ", max luminance "
              << cal.max_luminance << "\n"
              << "dE00 foveal vs peripheral over " << r.targets << " targets (8-bit drive): mean " << r.mean << ", p95 "
              << r.p95 << ", max " << r.max << "\n"
              << "wrote " << a->out << "\n";
  });
}

const Registrar reg{"color-calibrate", &install};

}  // namespace
}  // namespace cmd_color_calibrate
}  // namespace fovea::cli
