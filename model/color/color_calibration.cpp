#include "model/color/color_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

namespace fovea::color {

namespace {
constexpr const char* kChannelNames[3] = {"R", "G", "B"};

[[noreturn]] void bad(const std::string& m) {
  throw std::invalid_argument(m);
}

double number(const nlohmann::json& j, const std::string& where) {
  if (!j.is_number()) bad(where + " must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) bad(where + " is not finite");
  return v;
}

ChannelMeasurement parseChannel(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) bad(where + " must be an object with x, y and Y");
  ChannelMeasurement c;
  for (const char* k : {"x", "y", "Y"})
    if (!j.contains(k)) bad(where + "." + k + " is missing");
  c.xy = {number(j["x"], where + ".x"), number(j["y"], where + ".y")};
  if (c.xy.x < 0 || c.xy.y <= 0 || c.xy.x + c.xy.y > 1)
    bad(where + ": chromaticity (" + std::to_string(c.xy.x) + ", " + std::to_string(c.xy.y) +
        ") is outside the xy diagram");
  const auto& Y = j["Y"];
  if (!Y.is_array() || Y.size() != 256)
    bad(where + ".Y must hold 256 luminances (codes 0..255), has " + std::to_string(Y.is_array() ? Y.size() : 0));
  for (std::size_t i = 0; i < Y.size(); ++i) {
    c.Y.push_back(number(Y[i], where + ".Y[" + std::to_string(i) + "]"));
    if (c.Y.back() < 0) bad(where + ".Y[" + std::to_string(i) + "] is a negative luminance");
  }
  if (c.Y.back() <= c.Y.front()) bad(where + ".Y does not rise: Y[255] <= Y[0]");
  return c;
}

DisplayMeasurement parseDisplay(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) bad(where + " must be an object with R, G and B");
  DisplayMeasurement d;
  for (int c = 0; c < 3; ++c) {
    if (!j.contains(kChannelNames[c])) bad(where + "." + kChannelNames[c] + " is missing");
    d.channels[c] = parseChannel(j[kChannelNames[c]], where + "." + kChannelNames[c]);
  }
  return d;
}

nlohmann::json displayJson(const DisplayMeasurement& d) {
  nlohmann::json out = nlohmann::json::object();
  for (int c = 0; c < 3; ++c)
    out[kChannelNames[c]] = {{"x", d.channels[c].xy.x}, {"y", d.channels[c].xy.y}, {"Y", d.channels[c].Y}};
  return out;
}

Eigen::Matrix3d mixMatrix(const Triangle& t) {
  Eigen::Matrix3d m;
  for (int c = 0; c < 3; ++c) m.col(c) = xyYToXyz(t[c], 1.0);
  return m;
}

void requireNonDegenerate(const Triangle& t, const std::string& what) {
  if (triangleArea(t) < 1e-6) bad(what + " primaries are (nearly) collinear: no gamut");
}
}  // namespace

ColorMeasurements parseColorMeasurements(const nlohmann::json& j) {
  if (!j.is_object()) bad("colour measurements must be a JSON object");
  if (!j.contains("format") || !j["format"].is_string() || j["format"].get<std::string>() != "fovea-color-measurements")
    bad("format must be \"fovea-color-measurements\"");
  if (!j.contains("version") || !j["version"].is_number_integer() || j["version"].get<long long>() != 1)
    bad("version must be 1");
  for (const char* k : {"foveal", "peripheral"})
    if (!j.contains(k)) bad(std::string(k) + " is missing");
  return {parseDisplay(j["foveal"], "foveal"), parseDisplay(j["peripheral"], "peripheral")};
}

nlohmann::json toJson(const ColorMeasurements& m) {
  return {{"format", "fovea-color-measurements"},
          {"version", 1},
          {"foveal", displayJson(m.foveal)},
          {"peripheral", displayJson(m.peripheral)}};
}

Eigen::Vector3d DisplayModel::emitted(const Eigen::Vector3d& drive) const {
  Eigen::Vector3d lum;
  for (int c = 0; c < 3; ++c) lum[c] = curves[c].luminance(drive[c]);
  return mix * lum;
}

DisplayModel makeDisplayModel(const DisplayMeasurement& m) {
  DisplayModel d;
  for (int c = 0; c < 3; ++c) {
    d.primaries[c] = m.channels[c].xy;
    d.curves[c] = LuminanceCurve(m.channels[c].Y);
  }
  d.mix = mixMatrix(d.primaries);
  return d;
}

double fitGamma(const LuminanceCurve& curve) {
  const double peak = curve.peakLuminance();
  const double n = curve.maxCode();
  double sxx = 0, sxy = 0;
  int count = 0;
  for (int i = 1; i <= static_cast<int>(n); ++i) {
    const double yn = curve.luminance(i) / peak;
    if (yn < 0.01 || yn > 0.95) continue;
    const double lx = std::log(i / n), ly = std::log(yn);
    sxx += lx * lx;  // fit through the origin of log-log: Y/Ypeak = (code/n)^gamma
    sxy += lx * ly;
    ++count;
  }
  return count < 2 || sxx <= 0 ? std::nan("") : sxy / sxx;
}

ColorCalibration calibrateColor(const ColorMeasurements& m, const ColorCalibrationOptions& options) {
  if (!(options.gamma > 0) || !std::isfinite(options.gamma)) bad("gamma must be a positive number");
  ColorCalibration c;
  c.measurements = m;
  c.foveal = makeDisplayModel(m.foveal);
  c.peripheral = makeDisplayModel(m.peripheral);
  requireNonDegenerate(c.foveal.primaries, "foveal");
  requireNonDegenerate(c.peripheral.primaries, "peripheral");
  c.overlap = intersectTriangles(c.foveal.primaries, c.peripheral.primaries);
  if (c.overlap.empty()) bad("the two displays' gamuts do not overlap");
  Triangle reference;
  for (int k = 0; k < 3; ++k)
    reference[k] = {0.5 * (c.foveal.primaries[k].x + c.peripheral.primaries[k].x),
                    0.5 * (c.foveal.primaries[k].y + c.peripheral.primaries[k].y)};
  c.common = largestInscribedTriangle(c.overlap, reference);
  requireNonDegenerate(c.common, "common");
  c.common_mix = mixMatrix(c.common);
  c.white = options.white.value_or(kD65);
  c.gamma = options.gamma;
  if (!insideTriangle(c.common, c.white, 0.0))
    bad("white point (" + std::to_string(c.white.x) + ", " + std::to_string(c.white.y) +
        ") lies outside the common gamut");

  // Relative luminances of the common primaries that mix to a white of unit luminance.
  const Eigen::Vector3d whiteXyz = xyYToXyz(c.white, 1.0);
  const Eigen::Vector3d w = c.common_mix.colPivHouseholderQr().solve(whiteXyz);
  // Brightest white both displays reach: at RGB=(255,255,255) each display channel must
  // give (M_d^{-1} XYZ_white)_i * Y_max <= its peak. Because every common primary lies in
  // both gamuts, M_d^{-1} M_common has non-negative entries, so the full-white corner is
  // the most demanding target of the cube for every channel.
  double yMax = std::numeric_limits<double>::infinity();
  for (const DisplayModel* d : {&c.foveal, &c.peripheral}) {
    const Eigen::Vector3d need = d->mix.colPivHouseholderQr().solve(whiteXyz);
    for (int k = 0; k < 3; ++k) {
      if (need[k] <= 0) bad("white point is outside a display's gamut");
      yMax = std::min(yMax, d->curves[k].peakLuminance() / need[k]);
    }
  }
  c.max_luminance = yMax;
  c.kappa = w * yMax;
  return c;
}

Eigen::Vector3d ColorCalibration::targetXyz(const Eigen::Vector3d& rgb255) const {
  Eigen::Vector3d lum;
  for (int k = 0; k < 3; ++k) lum[k] = kappa[k] * std::pow(std::clamp(rgb255[k] / 255.0, 0.0, 1.0), gamma);  // S14
  return common_mix * lum;
}

Eigen::Vector3d ColorCalibration::drive(Display which, const Eigen::Vector3d& rgb255) const {
  const DisplayModel& d = display(which);
  const Eigen::Vector3d lum = d.mix.colPivHouseholderQr().solve(targetXyz(rgb255));  // S18
  Eigen::Vector3d code;
  for (int k = 0; k < 3; ++k) code[k] = d.curves[k].code(std::max(0.0, lum[k]));
  return code;
}

nlohmann::json toJson(const ColorCalibration& c) {
  auto xy = [](Xy p) { return nlohmann::json::array({p.x, p.y}); };
  nlohmann::json common = nlohmann::json::object(), overlap = nlohmann::json::array();
  nlohmann::json kappa = nlohmann::json::object();
  for (int k = 0; k < 3; ++k) {
    common[kChannelNames[k]] = xy(c.common[k]);
    kappa[kChannelNames[k]] = c.kappa[k];
  }
  for (const Xy& p : c.overlap) overlap.push_back(xy(p));
  return {{"format", "fovea-color-calibration"},
          {"version", 1},
          {"common_primaries_xy", common},
          {"white_xy", xy(c.white)},
          {"gamma", c.gamma},
          {"max_luminance", c.max_luminance},
          {"kappa", kappa},
          {"overlap_polygon_xy", overlap},
          {"measurements", toJson(c.measurements)}};
}

ColorCalibration calibrationFromJson(const nlohmann::json& j) {
  if (!j.is_object() || j.value("format", std::string()) != "fovea-color-calibration")
    bad("not a colour calibration file (format must be \"fovea-color-calibration\")");
  if (!j.contains("measurements")) bad("calibration file has no measurements");
  ColorCalibrationOptions o;
  if (!j.contains("white_xy") || !j["white_xy"].is_array() || j["white_xy"].size() != 2) bad("white_xy must be [x, y]");
  o.white = Xy{number(j["white_xy"][0], "white_xy[0]"), number(j["white_xy"][1], "white_xy[1]")};
  if (!j.contains("gamma")) bad("gamma is missing");
  o.gamma = number(j["gamma"], "gamma");
  // The derived quantities are recomputed from the embedded measurements (deterministic).
  return calibrateColor(parseColorMeasurements(j["measurements"]), o);
}

DeltaEReport deltaEBetweenDisplays(const ColorCalibration& c, int steps) {
  DeltaEReport r;
  const Eigen::Vector3d white = c.targetXyz({255, 255, 255});
  std::vector<double> quantised;
  double sumReal = 0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j)
      for (int k = 0; k < steps; ++k) {
        const Eigen::Vector3d rgb = Eigen::Vector3d(i, j, k) * (255.0 / (steps - 1));
        const Eigen::Vector3d df = c.drive(Display::Foveal, rgb), dp = c.drive(Display::Peripheral, rgb);
        const Eigen::Vector3d qf = df.array().round().matrix(), qp = dp.array().round().matrix();
        const double dq = deltaE2000(xyzToLab(c.foveal.emitted(qf), white), xyzToLab(c.peripheral.emitted(qp), white));
        const double dr = deltaE2000(xyzToLab(c.foveal.emitted(df), white), xyzToLab(c.peripheral.emitted(dp), white));
        if (quantised.empty() || dq > r.max) {
          r.max = dq;
          r.worst_rgb = rgb;
        }
        quantised.push_back(dq);
        sumReal += dr;
        r.max_real_drive = std::max(r.max_real_drive, dr);
      }
  r.targets = static_cast<int>(quantised.size());
  double sum = 0;
  for (double v : quantised) sum += v;
  r.mean = sum / r.targets;
  r.mean_real_drive = sumReal / r.targets;
  std::sort(quantised.begin(), quantised.end());
  r.p95 = quantised[static_cast<std::size_t>(std::floor(0.95 * (r.targets - 1)))];
  return r;
}

}  // namespace fovea::color
