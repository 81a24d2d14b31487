#pragma once
// Gaze calibration (seed C.4): a user-specific polynomial map from the pupil centre in the
// eye-camera image (pixels) to the monocular gaze (yaw, pitch in degrees), fitted by least
// squares to 5 (or 9) fixation targets, each pupil position averaged over 10 consecutive
// samples; accuracy and precision in degrees on held-out targets.
//
// Models (terms of the normalised pupil position u = (x - c_x)/s, v = (y - c_y)/s, with c
// the mean and s the RMS radius of the calibration pupil positions, for conditioning):
//   poly1    1, u, v                      (3 terms, >= 3 targets)
//   bilinear 1, u, v, uv                  (4 terms: the usual 5-point choice)
//   poly2    1, u, v, uv, u^2, v^2        (6 terms: the usual 9-point choice)
// The default follows the number of calibration targets: >= 9 poly2, >= 5 bilinear, else
// poly1 (Cerrolaza, Villanueva, Cabeza, "Taxonomic study of polynomial regressions applied
// to the calibration of video-oculographic systems", ETRA 2008).
//
// Temporal averaging: a target's averaged pupil position is the mean of its LAST `average`
// samples (default 10): the first samples after the target appears may still catch the
// saccade landing. Fewer samples are used whole.
//
// Accuracy (Holmqvist, Nystrom, Mulvey, "Eye tracker data quality", ETRA 2012): the angle
// between the target direction and the gaze mapped from the averaged pupil position.
// Precision: from the per-sample (unaveraged) gaze estimates of a held-out target, the RMS
// of the angles between successive samples (RMS-S2S) and the RMS angle to their mean
// direction (SD). Angles are great-circle angles between the gaze directions of
// scene_geometry.h's gazeDirection (yaw about +y, then pitch).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace fovea::gaze {

enum class GazeModel { Poly1, Bilinear, Poly2 };
const char* modelName(GazeModel m);
std::optional<GazeModel> modelFromName(const std::string& name);
int termCount(GazeModel m);
std::vector<std::string> termNames(GazeModel m);
// Default model for a number of calibration targets (>= 9 poly2, >= 5 bilinear, else poly1).
GazeModel defaultModel(int calibration_targets);

struct GazeTarget {
  std::string label;
  std::array<double, 2> target_deg{0, 0};  // yaw, pitch
  std::vector<Eigen::Vector2d> pupil_px;   // samples in time order
  bool holdout = false;                    // validation target, not used in the fit
};

// The samples file (docs/preview.md):
// {"format":"fovea-gaze-samples","version":1,
//  "camera":{"width_px":W,"height_px":H},                    (optional)
//  "targets":[{"label":"C","target_deg":[yaw,pitch],"holdout":false,
//              "pupil_px":[[x,y],...]},...]}
// Throws std::invalid_argument naming the offending key (NaN, missing or empty samples,
// wrong format tag or version).
std::vector<GazeTarget> parseGazeSamples(const nlohmann::json& j);
nlohmann::json gazeSamplesToJson(const std::vector<GazeTarget>& targets);

// Mean of the last `count` samples (all of them when fewer).
Eigen::Vector2d averagedPupil(const std::vector<Eigen::Vector2d>& samples, int count);

struct GazeMap {
  GazeModel model = GazeModel::Poly2;
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
  double scale_px = 1;
  Eigen::MatrixX2d coefficients;  // termCount rows; columns yaw, pitch (deg)
  std::array<double, 2> gazeDeg(const Eigen::Vector2d& pupil_px) const;
};

// Least-squares fit. Throws std::invalid_argument: fewer targets than terms, non-finite
// values, or pupil positions that leave the model undetermined (repeated or collinear).
GazeMap fitGazeMap(const std::vector<Eigen::Vector2d>& pupil_px, const std::vector<std::array<double, 2>>& gaze_deg,
                   GazeModel model);

// Great-circle angle between two gazes (degrees).
double angleBetweenDeg(const std::array<double, 2>& a, const std::array<double, 2>& b);

struct TargetResult {
  std::string label;
  std::array<double, 2> target_deg{0, 0}, estimate_deg{0, 0};
  double error_deg = 0;                                    // accuracy at this target
  double precision_rms_s2s_deg = 0, precision_sd_deg = 0;  // unaveraged samples
  int samples = 0;
  bool holdout = false;
};

struct GazeCalibrationOptions {
  std::optional<GazeModel> model;  // default: defaultModel(calibration targets)
  int average = 10;                // samples averaged per target
};

struct GazeCalibrationResult {
  GazeMap map;
  int calibration_targets = 0;
  double fit_rms_deg = 0;  // angular residual at the calibration targets
  // "holdout": the targets marked holdout; "leave-one-out": none marked, so each
  // calibration target in turn is left out of a refit and predicted by it.
  std::string validation;
  std::vector<TargetResult> validated;  // the held-out (or left-out) targets
  double accuracy_mean_deg = 0, accuracy_max_deg = 0;
  double precision_rms_s2s_deg = 0, precision_sd_deg = 0;  // RMS over the validated targets
};

// Throws std::invalid_argument (as fitGazeMap; also when leave-one-out cannot refit).
GazeCalibrationResult calibrateGaze(const std::vector<GazeTarget>& targets, const GazeCalibrationOptions& options = {});

}  // namespace fovea::gaze
