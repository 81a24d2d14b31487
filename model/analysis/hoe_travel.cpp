#include "model/analysis/hoe_travel.h"

#include "model/analysis/trace_evaluator.h"

namespace fovea {

XpRule sceneXpRule(const Scene& scene) {
  return parseXpRule(scene.view.xp_rule).value_or(XpRule::PlateauMiddle);
}

GazeStudyOptions hoeTravelStudyOptions(XpRule rule) {
  GazeStudyOptions o;  // sweep's: gazeStudyOptionsFrom() only sets the eye-box criterion, which x_p does not read
  o.xp_rule = rule;
  return o;
}

FovEvaluator hoeTravelEvaluator() {
  TraceEvaluatorOptions t;  // sweep's evaluatorFrom() defaults: edges, every laser, ours
  t.fov_method = FovMethod::Edges;
  return traceEvaluator(t);
}

HoeTravel hoeTravel(const Scene& scene, std::array<double, 2> gaze_deg, XpRule rule) {
  return hoeTravel(scene, gaze_deg, rule, hoeTravelEvaluator());
}

HoeTravel hoeTravel(const Scene& scene, std::array<double, 2> gaze_deg, XpRule rule, const FovEvaluator& eval) {
  const GazeStudyOptions o = hoeTravelStudyOptions(rule);
  HoeTravel t;
  for (int k = 0; k < 2; ++k) {
    if (gaze_deg[k] == 0.0) continue;
    const GazeSample s =
        optimiseShift(scene, eval, gaze_deg[k], k == 0 ? GazeAxis::Yaw : GazeAxis::Pitch, ShiftMethod::Hoe, o);
    t.shift_mm[k] = s.shift_mm;
    t.focus_axial_miss_mm[k] = s.focus_axial_miss_mm;
  }
  return t;
}

}  // namespace fovea
