#pragma once
// Multiple-display colour calibration (seed B.2.2): make the micro-OLED (foveal) and the
// laser projector seen through the HOE (peripheral) show the same colour for the same
// target RGB.
//
// Mixing (derived here; the seed's S15-S16 as printed repeat the G term in the
// denominator): a primary of chromaticity (x_c, y_c) at luminance Y_c has tristimulus
// Y_c * (x_c/y_c, 1, (1-x_c-y_c)/y_c). Tristimulus values add, so a mix is
//   XYZ = M * (Y_R, Y_G, Y_B)^T,  M's columns = (x_c/y_c, 1, (1-x_c-y_c)/y_c),
// with x = X/(X+Y+Z) and X+Y+Z = sum_c Y_c / y_c. The drive luminances of a display for a
// target XYZ are Y = M_display^{-1} XYZ (S18 is the same 3x3 system with its first two rows
// multiplied out by x_target and y_target).
//
// Calibration: common primaries inside the overlap of the two gamuts, the new gamma, the
// white point (D65 by default), white-balance coefficients kappa_c (the luminance of
// common primary c at full code, Eq. S14) chosen so that RGB = (255,255,255) is the white
// point and every target in the RGB cube is reachable by both displays (the brightest
// such white: max_luminance).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "model/color/colorimetry.h"
#include "model/color/gamut.h"
#include "model/color/luminance_curve.h"

namespace fovea::color {

struct ChannelMeasurement {
  Xy xy;
  std::vector<double> Y;  // luminance at code 0..255 (cd/m^2 or relative)
};
struct DisplayMeasurement {
  std::array<ChannelMeasurement, 3> channels;  // R, G, B
};
struct ColorMeasurements {
  DisplayMeasurement foveal, peripheral;
};

// Parses {"format":"fovea-color-measurements","version":1,"foveal":{...},"peripheral":{...}}.
// Throws std::invalid_argument naming the offending key.
ColorMeasurements parseColorMeasurements(const nlohmann::json& j);
nlohmann::json toJson(const ColorMeasurements& m);

enum class Display { Foveal, Peripheral };

struct DisplayModel {
  Triangle primaries;
  Eigen::Matrix3d mix;  // columns: XYZ per unit luminance of each primary
  std::array<LuminanceCurve, 3> curves;
  // XYZ emitted (above black) at real drive values on the display's code scale.
  Eigen::Vector3d emitted(const Eigen::Vector3d& drive) const;
};
DisplayModel makeDisplayModel(const DisplayMeasurement& m);

struct ColorCalibrationOptions {
  std::optional<Xy> white;  // default D65
  double gamma = 2.2;       // gamma of the calibrated (common) display
};

struct ColorCalibration {
  ColorMeasurements measurements;
  DisplayModel foveal, peripheral;
  std::vector<Xy> overlap;  // overlapped gamut polygon (CCW)
  Triangle common;          // common primaries R, G, B
  Eigen::Matrix3d common_mix;
  Xy white;
  double gamma = 2.2;
  Eigen::Vector3d kappa;     // luminance of each common primary at full code (S14)
  double max_luminance = 0;  // luminance of RGB = (255,255,255)

  const DisplayModel& display(Display d) const { return d == Display::Foveal ? foveal : peripheral; }
  // Target XYZ of an RGB triple on the 0..255 scale (Eq. S14 then the mixing matrix).
  Eigen::Vector3d targetXyz(const Eigen::Vector3d& rgb255) const;
  // Drive values (real, on that display's own code scale) that reproduce the target.
  Eigen::Vector3d drive(Display d, const Eigen::Vector3d& rgb255) const;
};

// Throws std::invalid_argument for degenerate primaries, disjoint gamuts, a white point
// outside the common gamut, or a non-positive gamma.
ColorCalibration calibrateColor(const ColorMeasurements& m, const ColorCalibrationOptions& options = {});

// The calibration file written by `fovea-cli color-calibrate` (it embeds the measurements,
// so it alone rebuilds the look-up tables).
nlohmann::json toJson(const ColorCalibration& c);
ColorCalibration calibrationFromJson(const nlohmann::json& j);

// Least-squares gamma of one measured curve: log-log fit of Y/Ypeak against code/255 over
// the codes whose normalised luminance lies in [0.01, 0.95].
double fitGamma(const LuminanceCurve& curve);

struct DeltaEReport {
  int targets = 0;
  double mean = 0, p95 = 0, max = 0;               // foveal vs peripheral, 8-bit drive codes
  double mean_real_drive = 0, max_real_drive = 0;  // same with unquantised drive values
  Eigen::Vector3d worst_rgb = Eigen::Vector3d::Zero();
};
// Delta E 2000 between what the two displays emit for an n x n x n grid of targets (CIELAB
// relative to the calibrated white), with drive values rounded to integer codes as a
// real 8-bit display would show them, and without rounding.
DeltaEReport deltaEBetweenDisplays(const ColorCalibration& c, int steps_per_channel = 9);

}  // namespace fovea::color
