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
      const PupilDetection d = detectPupil(f.image, o.detector);
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

}  // namespace fovea::gaze
