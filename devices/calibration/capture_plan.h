#pragma once
// Calibration capture plans (seed B.2, C): the sequence of bench poses and display patterns a
// calibration needs, as data. The studio's capture wizard and `fovea-cli calibrate` both
// run them through a CaptureSession (capture_session.h).
//
//  - geometric: for each gaze of the list, the camera turns to the gaze, the HOE stages go to
//    x_p(alpha) and the micro-OLED stages to x_f(alpha); the projector shows a checkerboard
//    (micro-OLED off), then the micro-OLED does (projector off). A display whose stage target
//    leaves the binding's soft limits at a gaze is skipped there (and reported).
//  - colour: bench at zero gaze; on each display a black patch, R, G and B ramps and white
//    (the patch sequence a spectroradiometer measures; its readings are imported as a
//    "fovea-color-measurements" file).
//  - gaze: a fixation dot on the micro-OLED, recentred by its stages on five gazes (centre,
//    left, right, up, down); the camera turns to each where its stages allow.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/image/display_pattern.h"
#include "model/physics/display_camera_map.h"
#include "model/scene/scene.h"

namespace fovea::devices {

enum class CaptureKind { Geometric, Color, Gaze };
const char* toString(CaptureKind k);
std::optional<CaptureKind> captureKindFromString(const std::string& s);

struct StageTarget {
  std::string element, axis;
  double value = 0;  // element coordinate (mm or deg)
  bool operator==(const StageTarget&) const = default;
};

struct CaptureStep {
  std::string id;  // unique in the plan: "geometric/peripheral/yaw-10"
  CaptureKind kind = CaptureKind::Geometric;
  BenchDisplay display = BenchDisplay::Peripheral;  // the display that is lit
  std::array<double, 2> gaze_deg{0, 0};
  std::vector<StageTarget> targets;  // only coordinates the scene binds to a stage
  image::DisplayPattern pattern;     // on `display`; the other display is off
  std::string instruction;           // for the operator
  bool operator==(const CaptureStep&) const = default;
};
nlohmann::json toJson(const CaptureStep& s);
// Throws std::invalid_argument "PATH.key: problem" (PATH: where the step is, e.g. "steps[3]").
CaptureStep captureStepFromJson(const nlohmann::json& j, const std::string& path = "step");

struct GeometricPlanOptions {
  std::vector<double> gazes_yaw_deg;  // default: 5 over the scene's gaze range
  std::array<int, 2> peripheral_squares{7, 9}, foveal_squares{8, 5};
  double peripheral_size = 0.75;  // of the projector region on the HOE (peripheralBoard)
  double foveal_fill = 0.9;       // board size as a fraction of the micro-OLED
  // x_p(alpha) of the HOE for a gaze (yaw, pitch): default geometricHoeShiftForGaze(); the
  // studio and the CLI pass the analyses' optimiseShift.
  std::function<std::array<double, 2>(std::array<double, 2>)> hoe_shift;
};

// The calibration boards. On the projector: `size` of the largest rectangle of the board's
// aspect inside the part of its image that lands on the HOE plate (projectorRegionOnHoe,
// 5 mm in from the plate's edges, so the stages' shifts keep it on the plate), centred on
// the pixel the gaze's line of sight meets as far as it stays inside that rectangle (each
// gaze calibrates the display around where the eye looks). On the micro-OLED: centred,
// `fill` of the display (its stages recentre it on the gaze).
image::DisplayPattern peripheralBoard(const Scene& scene, std::array<double, 2> gaze_deg = {0, 0},
                                      std::array<int, 2> squares = {7, 9}, double size = 0.75);
image::DisplayPattern fovealBoard(const Scene& scene, std::array<int, 2> squares = {8, 5}, double fill = 0.9);

struct Plan {
  std::vector<CaptureStep> steps;
  std::vector<std::string> skipped;  // why a display / gaze is left out
};

Plan geometricPlan(const Scene& scene, const GeometricPlanOptions& options = {});
Plan colorPlan(const Scene& scene, std::vector<double> levels = {0.25, 0.5, 0.75, 1.0});
Plan gazePlan(const Scene& scene, double offset_deg = 10.0);

// x_p(alpha) from the analyses: the one x_p source (model/analysis/hoe_travel.h hoeTravel
// with the scene's view.xp_rule, what `sweep` reports), yaw -> HOE x and pitch -> HOE y; a
// zero gaze component keeps that shift at 0.
std::function<std::array<double, 2>(std::array<double, 2>)> analysedHoeShift(const Scene& scene);

// Whether an element coordinate is inside its binding's soft limits (true when unbound).
bool withinSoftLimits(const Scene& scene, const StageTarget& t);
bool isBound(const Scene& scene, const std::string& element, const std::string& axis);

}  // namespace fovea::devices
