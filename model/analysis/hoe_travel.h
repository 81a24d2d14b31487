#pragma once
// The one source of the HOE travel x_p(alpha) the product applies: the studio's live trace
// with "HOE follows gaze", the design report, the calibration capture plan (studio wizard and
// `fovea-cli calibrate`), the virtual bench's follow-gaze table. It is what `fovea-cli sweep`
// reports: optimiseShift (gaze_studies.h) on the exact FOV evaluator (fov_edges.h, every
// projector laser, threshold 0.1, edges to 0.005 deg) with the sweep's default study options
// and the chosen x_p rule. So at a gaze `sweep` samples, every caller applies sweep's x_p.
//
// Per component, as the sweep searches one axis at a time: yaw -> HOE local x (searched at
// pitch 0), pitch -> HOE local y (at yaw 0); a zero gaze component keeps its shift at 0 (the
// design position), so "HOE follows gaze" at zero gaze traces the unmoved design.

#include <array>
#include <limits>
#include <string>

#include "model/analysis/gaze_studies.h"
#include "model/scene/scene.h"

namespace fovea {

// The scene's rule (view.xp_rule); plateau-middle when unset or unknown.
XpRule sceneXpRule(const Scene& scene);

// The study options and evaluator every x_p caller uses (those of `sweep` by default).
GazeStudyOptions hoeTravelStudyOptions(XpRule rule);
FovEvaluator hoeTravelEvaluator();

struct HoeTravel {
  std::array<double, 2> shift_mm{0, 0};  // HOE local x, y
  // FollowFocus: the focus's axial miss of the pupil centre per component (NaN otherwise or at a zero component).
  std::array<double, 2> focus_axial_miss_mm{std::numeric_limits<double>::quiet_NaN(),
                                            std::numeric_limits<double>::quiet_NaN()};
};

// x_p for a (yaw, pitch) gaze. `eval` defaults to hoeTravelEvaluator(); a caller may wrap it
// (the live trace checks for a superseded request between evaluations) but must not change it.
HoeTravel hoeTravel(const Scene& scene, std::array<double, 2> gaze_deg, XpRule rule);
HoeTravel hoeTravel(const Scene& scene, std::array<double, 2> gaze_deg, XpRule rule, const FovEvaluator& eval);

}  // namespace fovea
