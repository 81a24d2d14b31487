#include "model/gaze/tracked_calibration.h"

#include <random>
#include <stdexcept>
#include <string>

namespace fovea::gaze {

TrackedCalibration calibrateWithTracker(const TrackedCalibrationOptions& o) {
  struct Spot {
    double yaw, pitch;
    bool holdout;
  };
  std::vector<Spot> spots{{0, 0, false}, {-15, -10, false}, {15, -10, false}, {-15, 10, false}, {15, 10, false}};
  for (const auto& [y, p] : std::vector<std::pair<double, double>>{{-15, 0}, {15, 0}, {0, -10}, {0, 10}})
    spots.push_back({y, p, true});
  for (const auto& [y, p] : std::vector<std::pair<double, double>>{{-7.5, -5}, {7.5, -5}, {-7.5, 5}, {7.5, 5}})
    spots.push_back({y, p, true});

  std::mt19937 rng(o.seed);
  std::normal_distribution<double> jitter(0.0, o.fixation_jitter_deg);
  EyeFrameSpec spec;
  spec.leds_mm = ledRing(o.camera, o.leds, o.led_ring_radius_mm);
  TrackedCalibration out;
  for (const Spot& s : spots) {
    GazeTarget t;
    t.label = std::to_string(static_cast<int>(s.yaw * 10) / 10.0) + "," + std::to_string(static_cast<int>(s.pitch));
    t.target_deg = {s.yaw, s.pitch};
    t.holdout = s.holdout;
    for (int i = 0;
         i < o.samples_per_target + o.extra_frames && static_cast<int>(t.pupil_px.size()) < o.samples_per_target; ++i) {
      spec.gaze_deg = {s.yaw + jitter(rng), s.pitch + jitter(rng)};
      spec.seed = static_cast<std::uint32_t>(rng());
      const EyeFrame f = renderEyeFrame(o.camera, o.eye, spec);
      const PupilDetection d = detectPupilWith(o.detector_kind, f.image, o.detector);
      ++out.frames;
      if (!d.found || d.confidence < o.min_confidence) {
        ++out.rejected;
        continue;
      }
      t.pupil_px.emplace_back(d.ellipse.centre.x, d.ellipse.centre.y);
    }
    if (t.pupil_px.size() < 3)
      throw std::invalid_argument("target " + t.label + ": only " + std::to_string(t.pupil_px.size()) +
                                  " confident pupil detections");
    out.targets.push_back(std::move(t));
  }
  GazeCalibrationOptions co;
  co.average = o.samples_per_target;
  out.result = calibrateGaze(out.targets, co);
  return out;
}

nlohmann::json trackedCalibrationJson(const TrackedCalibration& c, const TrackedCalibrationOptions& o) {
  const GazeCalibrationResult& r = c.result;
  nlohmann::json per = nlohmann::json::array();
  for (const TargetResult& t : r.validated)
    per.push_back({{"label", t.label},
                   {"target_deg", t.target_deg},
                   {"estimate_deg", t.estimate_deg},
                   {"error_deg", t.error_deg},
                   {"precision_rms_s2s_deg", t.precision_rms_s2s_deg}});
  return {{"method",
           "pupil detector on rendered IR eye-camera frames; each target the average of its accepted samples, "
           "frames below min_confidence rejected; accuracy and precision on the held-out grid (seed C.4)"},
          {"detector", detectorName(o.detector_kind)},
          {"targets", r.calibration_targets},
          {"samples_per_target", o.samples_per_target},
          {"min_confidence", o.min_confidence},
          {"accuracy_mean_deg", r.accuracy_mean_deg},
          {"accuracy_max_deg", r.accuracy_max_deg},
          {"precision_rms_s2s_deg", r.precision_rms_s2s_deg},
          {"precision_sd_deg", r.precision_sd_deg},
          {"held_out_targets", r.validated.size()},
          {"validation", r.validation},
          {"fit_rms_deg", r.fit_rms_deg},
          {"frames", c.frames},
          {"rejected", c.rejected},
          {"seed", o.seed},
          {"held_out", per}};
}

}  // namespace fovea::gaze
