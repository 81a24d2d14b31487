#include "devices/bench/closed_gaze_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "devices/apt/stage_models.h"
#include "devices/bench/followed_axis.h"
#include "devices/virtual/motion_profile.h"
#include "model/gaze/pupil_detector.h"
#include "model/gaze/tracked_calibration.h"
#include "model/physics/display_camera_map.h"
#include "model/units.h"

namespace fovea::devices {
namespace {

// Minimum-jerk position fraction s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 (Flash & Hogan 1985).
double minimumJerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
}

}  // namespace

apt::StageModel stageModelFor(const Scene& scene, const std::string& element, const ClosedLoopOptions& o,
                              std::string& name) {
  name = o.stage_model.value_or("");
  if (name.empty())
    for (const auto& b : scene.stages)
      if (b.element == element && (b.axis == "x" || b.axis == "y")) name = b.stage_model;
  if (name.empty()) name = "MTS25-Z8";
  const auto m = apt::findStage(name);
  if (!m || m->rotation) throw std::invalid_argument("unknown linear stage model '" + name + "'");
  return *m;
}

namespace {

// Fraction of a disc of radius e, centred d from the centre of a disc of radius p, inside it.
double discOverlap(double d, double e, double p) {
  if (d >= e + p) return 0;
  if (d <= std::abs(p - e)) return e <= p ? 1.0 : (p * p) / (e * e);
  const double a1 = e * e * std::acos((d * d + e * e - p * p) / (2 * d * e));
  const double a2 = p * p * std::acos((d * d + p * p - e * e) / (2 * d * p));
  const double a3 = 0.5 * std::sqrt((-d + e + p) * (d + e - p) * (d - e + p) * (d + e + p));
  return (a1 + a2 - a3) / (kPi * e * e);
}

}  // namespace

std::array<double, 2> hoeShiftInOwnFrame(const Scene& scene, std::array<double, 2> gaze_deg, bool mirrored_frame) {
  if (!mirrored_frame) return geometricHoeShiftForGaze(scene, gaze_deg);
  const auto s = geometricHoeShiftForGaze(scene, {0.0 - gaze_deg[0], gaze_deg[1]});
  return {0.0 - s[0], s[1]};
}

double mainSequencePeakVelocity(double amplitude_deg) {
  return 700.0 * (1 - std::exp(-amplitude_deg / 10.0));
}

double saccadeDuration(double amplitude_deg) {
  return amplitude_deg > 0 ? 1.875 * amplitude_deg / mainSequencePeakVelocity(amplitude_deg) : 0;
}

std::array<double, 2> EyeTrajectory::gazeAt(double t) const {
  if (path) return path(t);
  std::array<double, 2> g{0, 0};
  for (const auto& s : saccades) {
    if (t < s.onset_s) break;
    const double f = minimumJerk((t - s.onset_s) / s.duration_s);
    g = {s.from_deg[0] + f * (s.to_deg[0] - s.from_deg[0]), s.from_deg[1] + f * (s.to_deg[1] - s.from_deg[1])};
  }
  return g;
}

EyeTrajectory makeSaccadeTrajectory(const Scene& scene, const ClosedLoopOptions& o) {
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> u(0, 1);
  const auto in = [&](double a, double b) { return a + (b - a) * u(rng); };
  const double lo = scene.eye.gaze_range_deg[0], hi = scene.eye.gaze_range_deg[1];
  EyeTrajectory tr;
  std::array<double, 2> g{0, 0};
  double t = 0;
  for (int i = 0; i < o.saccades; ++i) {
    t += in(o.fixation_min_s, o.fixation_max_s);
    SaccadeEvent s;
    s.from_deg = g;
    for (int attempt = 0; attempt < 100; ++attempt) {
      s.amplitude_deg = in(o.amplitude_min_deg, o.amplitude_max_deg);
      const double dir = in(0, 2 * kPi);
      s.to_deg = {g[0] + s.amplitude_deg * std::cos(dir), g[1] + s.amplitude_deg * std::sin(dir)};
      if (s.to_deg[0] >= lo && s.to_deg[0] <= hi && s.to_deg[1] >= lo && s.to_deg[1] <= hi) break;
      s.to_deg = {0, 0};  // no valid direction: back to the centre
    }
    s.amplitude_deg = gaze::angleBetweenDeg(s.from_deg, s.to_deg);
    s.onset_s = t;
    s.duration_s = saccadeDuration(s.amplitude_deg);
    s.peak_velocity_deg_s = mainSequencePeakVelocity(s.amplitude_deg);
    t += s.duration_s;
    g = s.to_deg;
    tr.saccades.push_back(s);
  }
  tr.end_s = t + o.fixation_max_s;
  return tr;
}

Stats statsOf(std::vector<double> v) {
  Stats s;
  s.count = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  s.p95 = v[std::min(v.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(v.size())) - 1))];
  s.max = v.back();
  return s;
}

TrackedRun trackTrajectory(const Scene& scene, const ClosedLoopOptions& o) {
  return trackEyeTrajectory(scene, o, makeSaccadeTrajectory(scene, o));
}

TrackedRun trackEyeTrajectory(const Scene& scene, const ClosedLoopOptions& o, EyeTrajectory trajectory) {
  TrackedRun run;
  run.trajectory = std::move(trajectory);
  gaze::EyeAppearance eye;
  eye.pupil_diameter_mm = scene.eye.pupil_diameter_mm;
  gaze::TrackedCalibrationOptions co;
  co.camera = o.camera;
  co.eye = eye;
  co.leds = o.leds;
  co.seed = o.seed;
  co.detector_kind = o.detector;
  const gaze::TrackedCalibration cal = gaze::calibrateWithTracker(co);
  run.calibration_accuracy_deg = cal.result.accuracy_mean_deg;
  run.calibration_precision_deg = cal.result.precision_rms_s2s_deg;
  run.calibration_precision_sd_deg = cal.result.precision_sd_deg;

  gaze::EyeFrameSpec spec;
  spec.leds_mm = gaze::ledRing(o.camera, o.leds, co.led_ring_radius_mm);
  spec.moving = true;
  const double period = 1.0 / o.camera_fps;
  for (int k = 0; k * period < run.trajectory.end_s; ++k) {
    const double t0 = k * period;
    spec.gaze_deg = run.trajectory.gazeAt(t0);
    spec.gaze_end_deg = run.trajectory.gazeAt(t0 + o.exposure_s);
    spec.seed = o.seed * 7919u + static_cast<std::uint32_t>(k);
    const gaze::EyeFrame f = gaze::renderEyeFrame(o.camera, eye, spec);
    const auto w0 = std::chrono::steady_clock::now();
    const gaze::PupilDetection d = gaze::detectPupilWith(o.detector, f.image);
    const auto w1 = std::chrono::steady_clock::now();
    TrackedFrame tf;
    tf.exposure_start_s = t0;
    tf.true_gaze_deg = f.truth.gaze_deg;
    tf.found = d.found && d.confidence >= o.min_confidence;
    tf.confidence = d.confidence;
    if (tf.found) tf.gaze_deg = cal.result.map.gazeDeg({d.ellipse.centre.x, d.ellipse.centre.y});
    tf.detect_wall_s = std::chrono::duration<double>(w1 - w0).count();
    run.frames.push_back(tf);
  }
  return run;
}

ClosedLoopResult simulateStages(const Scene& scene, const TrackedRun& run, const ClosedLoopOptions& o) {
  ClosedLoopResult r;
  const apt::StageModel hoe_model = stageModelFor(scene, "hoe", o, r.hoe_stage);
  const apt::StageModel oled_model = stageModelFor(scene, "foveal_display", o, r.oled_stage);
  FollowedAxis hoe_x(hoe_model.max_velocity, hoe_model.max_acceleration, o.deadband_mm),
      hoe_y(hoe_model.max_velocity, hoe_model.max_acceleration, o.deadband_mm);
  FollowedAxis oled_x(oled_model.max_velocity, oled_model.max_acceleration, o.deadband_mm),
      oled_y(oled_model.max_velocity, oled_model.max_acceleration, o.deadband_mm);

  r.capture_s = o.exposure_s + o.readout_s;
  r.detect_s = o.detect_s;
  r.map_s = o.map_s;
  r.command_s = o.command_s;
  r.extra_latency_s = o.extra_latency_s;
  r.latency_to_command_s = r.capture_s + r.detect_s + r.map_s + r.extra_latency_s + r.command_s;
  r.calibration_accuracy_deg = run.calibration_accuracy_deg;
  r.calibration_precision_deg = run.calibration_precision_deg;
  r.saccades = run.trajectory.saccades;
  std::vector<double> detect_wall;
  for (const auto& f : run.frames) detect_wall.push_back(f.detect_wall_s);
  const Stats dw = statsOf(detect_wall);
  r.detect_measured_mean_s = dw.mean;
  r.detect_measured_max_s = dw.max;
  r.frames = static_cast<int>(run.frames.size());

  // Inverse of x_f = (d_f + r) tan(alpha) / M per axis (eye_camera.h's fovealShiftForGaze).
  const double k = fovealShiftForGaze(scene, {10, 0})[0] / std::tan(10 * kDeg);
  const double pupil_r = scene.eye.pupil_diameter_mm / 2, focus_r = scene.projector.exit_pupil_diameter_mm / 2;

  std::vector<double> inset_err, hoe_err;
  std::size_t next_frame = 0;
  const double step = o.eval_step_s;
  std::vector<double> settle, hoe_moves, oled_moves;
  std::size_t saccade_i = 0;
  double last_beyond = -1, off_fovea_here = 0, interval_start = -1;
  for (double t = 0; t < run.trajectory.end_s; t += step) {
    // Commands issued up to t.
    while (next_frame < run.frames.size() && run.frames[next_frame].exposure_start_s + r.latency_to_command_s <= t) {
      const TrackedFrame& f = run.frames[next_frame++];
      if (!f.found) continue;
      ++r.frames_found;
      const double tc = f.exposure_start_s + r.latency_to_command_s;
      const auto hoe = hoeShiftInOwnFrame(scene, f.gaze_deg, o.mirrored_frame);
      const auto oled = fovealShiftForGaze(scene, f.gaze_deg);
      hoe_x.command(tc, hoe[0]);
      hoe_y.command(tc, hoe[1]);
      oled_x.command(tc, oled[0]);
      oled_y.command(tc, oled[1]);
    }
    const auto g = run.trajectory.gazeAt(t);
    const std::array<double, 2> inset{std::atan(oled_x.position(t) / k) / kDeg,
                                      std::atan(oled_y.position(t) / k) / kDeg};
    const double err = gaze::angleBetweenDeg(g, inset);
    inset_err.push_back(err);
    if (err > scene.eye.fovea_radius_deg) {
      r.time_off_fovea_s += step;
      if (saccade_i < r.saccades.size() && t >= r.saccades[saccade_i].onset_s) off_fovea_here += step;
    }
    if (saccade_i < r.saccades.size() && t >= r.saccades[saccade_i].onset_s && interval_start < 0) interval_start = t;
    if (err > o.settle_tolerance_deg) r.time_beyond_tolerance_s += step, last_beyond = t;
    const auto xp = hoeShiftInOwnFrame(scene, g, o.mirrored_frame);
    const double d = std::hypot(hoe_x.position(t) - xp[0], hoe_y.position(t) - xp[1]);
    hoe_err.push_back(d);
    const double inside = discOverlap(d, focus_r, pupil_r);
    if (inside < 1) r.fov_partly_lost_s += step;
    if (inside <= 0) r.fov_lost_s += step;
    r.mean_light_lost += (1 - inside) * step;
    // Per saccade, at the next onset (or the end): settle time and the stage move times.
    const bool next_onset = saccade_i + 1 < r.saccades.size() && t + step >= r.saccades[saccade_i + 1].onset_s;
    const bool end = t + step >= run.trajectory.end_s;
    if (saccade_i < r.saccades.size() && (next_onset || end) && t >= r.saccades[saccade_i].onset_s) {
      const auto& s = r.saccades[saccade_i];
      if (last_beyond >= t - 0.5 * step)
        ++r.unsettled;  // still off when the next saccade starts (or the run ends)
      else
        settle.push_back(std::max(0.0, last_beyond + step - s.onset_s));
      const double cmd = s.onset_s + r.latency_to_command_s;
      hoe_moves.push_back(std::max(0.0, std::max(hoe_x.busyUntil(), hoe_y.busyUntil()) - cmd));
      oled_moves.push_back(std::max(0.0, std::max(oled_x.busyUntil(), oled_y.busyUntil()) - cmd));
      r.off_fovea_per_saccade_s.push_back(off_fovea_here);
      r.interval_per_saccade_s.push_back(t + step - interval_start);
      ++saccade_i;
      last_beyond = -1;
      off_fovea_here = 0;
      interval_start = -1;
    }
  }
  r.duration_s = run.trajectory.end_s;
  r.mean_light_lost /= std::max(r.duration_s, 1e-12);
  r.inset_error_deg = statsOf(inset_err);
  r.hoe_error_mm = statsOf(hoe_err);
  r.settle_s = statsOf(settle);
  r.hoe_move_s = statsOf(hoe_moves);
  r.oled_move_s = statsOf(oled_moves);
  return r;
}

}  // namespace fovea::devices
