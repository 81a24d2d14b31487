#include "devices/bench/binocular_loop.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>

#include "devices/bench/followed_axis.h"
#include "devices/virtual/motion_profile.h"
#include "model/gaze/gaze_calibration.h"
#include "model/physics/display_camera_map.h"
#include "model/scene/eye_scene.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea::devices {
namespace {

// Minimum-jerk fraction (Flash & Hogan 1985), as the monocular loop's saccades.
double binocularMinimumJerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
}

// One fixation change of the cyclopean eye: direction by a saccade, vergence by vergence.h.
struct FixationSegment {
  double onset_s = 0, saccade_s = 0;
  std::array<double, 2> from_dir{0, 0}, to_dir{0, 0};
  double from_vergence_deg = 0, to_vergence_deg = 0;
};

struct BinocularSchedule {
  gaze::BinocularGeometry geometry;
  gaze::VergenceDynamics dynamics;
  FixationSegment start;  // before the first onset
  std::vector<FixationSegment> segments;
  double end_s = 0;

  const FixationSegment& segmentAt(double t) const {
    const FixationSegment* s = &start;
    for (const auto& seg : segments) {
      if (t < seg.onset_s) break;
      s = &seg;
    }
    return *s;
  }
  std::array<double, 2> directionAt(double t) const {
    const FixationSegment& s = segmentAt(t);
    const double f = s.saccade_s > 0 ? binocularMinimumJerk((t - s.onset_s) / s.saccade_s) : 1.0;
    return {s.from_dir[0] + f * (s.to_dir[0] - s.from_dir[0]), s.from_dir[1] + f * (s.to_dir[1] - s.from_dir[1])};
  }
  double vergenceAt(double t) const {
    const FixationSegment& s = segmentAt(t);
    return gaze::vergenceAngleAt(dynamics, s.from_vergence_deg, s.to_vergence_deg, t - s.onset_s);
  }
  // The point the eyes fixate at time t (head frame).
  Eigen::Vector3d pointAt(double t) const {
    const auto d = directionAt(t);
    return gazeDirection(d[0], d[1]) * gaze::distanceForVergenceMm(geometry, vergenceAt(t));
  }
};

std::array<double, 2> mirrorGaze(const std::array<double, 2>& g) {
  return {-g[0], g[1]};
}

// The dioptric error statistics (mean, SD) of a sample.
std::array<double, 2> meanSd(const std::vector<double>& v) {
  if (v.empty()) return {0, 0};
  double m = 0;
  for (double x : v) m += x;
  m /= static_cast<double>(v.size());
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return {m, v.size() > 1 ? std::sqrt(s / static_cast<double>(v.size() - 1)) : 0.0};
}

}  // namespace

std::vector<BinocularFixation> randomFixations(int n, std::uint32_t seed, double near_mm, double far_mm) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const auto in = [&](double a, double b) { return a + (b - a) * u(rng); };
  std::vector<BinocularFixation> out;
  for (int i = 0; i < n; ++i) {
    BinocularFixation f;
    f.distance_mm = 1000.0 / in(1000.0 / far_mm, 1000.0 / near_mm);
    f.direction_deg = {in(-12, 12), in(-8, 8)};
    f.hold_s = in(0.8, 1.4);
    out.push_back(f);
  }
  return out;
}

BinocularResult runBinocularLoop(const Scene& scene, const std::vector<BinocularFixation>& fixations,
                                 const BinocularOptions& o) {
  if (scene.binocular)
    return runBinocularLoop(eyeScene(scene, EyeSide::Left), eyeScene(scene, EyeSide::Right), fixations, o);
  // A monocular scene: its train is the right eye's, the left one its mirror about the plane
  // ipd / 2 nasal of the right eye's rotation centre (eye_scene.h's midPlaneX).
  const double mid_plane_x_mm =
      scene.hoe.pose.position_mm[0] + scene.eye.lateral_offset_mm[0] - o.geometry.ipd_mm / 2.0;
  return runBinocularLoop(mirroredScene(scene, mid_plane_x_mm), scene, fixations, o);
}

BinocularResult runBinocularLoop(const Scene& left, const Scene& right, const std::vector<BinocularFixation>& fixations,
                                 const BinocularOptions& o) {
  if (fixations.empty()) throw std::invalid_argument("no fixations");
  BinocularResult r;
  auto sched = std::make_shared<BinocularSchedule>();
  sched->geometry = o.geometry;
  sched->dynamics = o.dynamics;
  sched->start.from_vergence_deg = sched->start.to_vergence_deg =
      gaze::vergenceForDistanceDeg(o.geometry, o.start_distance_mm);
  double t = o.start_hold_s;
  for (const auto& f : fixations) {
    FixationSegment s;
    s.onset_s = t;
    s.from_dir = sched->directionAt(t);
    s.from_vergence_deg = sched->vergenceAt(t);
    s.to_dir = f.direction_deg;
    s.to_vergence_deg = gaze::vergenceForDistanceDeg(o.geometry, f.distance_mm);
    s.saccade_s = saccadeDuration(gaze::angleBetweenDeg(s.from_dir, s.to_dir));
    sched->segments.push_back(s);
    t += f.hold_s;
  }
  sched->end_s = t;
  r.duration_s = t;

  const std::array<const Scene*, 2> scenes{&left, &right};
  const std::array<double, 2> radii{left.eye.eyeball_diameter_mm / 2, right.eye.eyeball_diameter_mm / 2};
  const std::array<Eigen::Vector3d, 2> centres{o.geometry.leftCentre(), o.geometry.rightCentre()};
  const std::array<std::uint32_t, 2> seeds{o.seed_left, o.seed_right};
  // Gaze of eye e (0 left, 1 right) in its own train's frame (the left one mirrored).
  auto ownGaze = [sched, centres](int e, double time) {
    const auto g = gaze::gazeTowardsDeg(centres[static_cast<std::size_t>(e)], sched->pointAt(time));
    return e == 0 ? mirrorGaze(g) : g;
  };

  // Per eye: the monocular loop on its own train. The two eyes' trackers are independent (own
  // seeds, own calibration, thread-local detectors), so the right eye runs on a second thread:
  // the same numbers, in about half the wall time on two cores.
  auto optionsFor = [&](int e) {
    ClosedLoopOptions oe = o.loop;
    oe.seed = seeds[static_cast<std::size_t>(e)];
    oe.mirrored_frame = e == 0;  // the left train in the bench frame, its gazes and targets mirrored
    return oe;
  };
  auto trackEye = [&](int e) -> TrackedRun {
    const ClosedLoopOptions oe = optionsFor(e);
    EyeTrajectory traj;
    traj.end_s = sched->end_s;
    traj.path = [ownGaze, e](double time) { return ownGaze(e, time); };
    for (const auto& s : sched->segments) {
      SaccadeEvent ev;
      ev.onset_s = s.onset_s;
      ev.duration_s = std::max(s.saccade_s, 1e-3);
      ev.from_deg = ownGaze(e, s.onset_s);
      ev.to_deg = ownGaze(e, s.onset_s + 10.0);  // the settled gaze (vergence done)
      ev.amplitude_deg = gaze::angleBetweenDeg(ev.from_deg, ev.to_deg);
      ev.peak_velocity_deg_s = mainSequencePeakVelocity(ev.amplitude_deg);
      traj.saccades.push_back(ev);
    }
    if (o.track) return trackEyeTrajectory(*scenes[static_cast<std::size_t>(e)], oe, traj);
    // Synthetic tracker: the true gaze at mid-exposure plus Gaussian noise per axis.
    TrackedRun run;
    run.trajectory = traj;
    std::mt19937 rng(oe.seed);
    std::normal_distribution<double> noise(0, o.synthetic_sigma_deg);
    const double period = 1.0 / oe.camera_fps;
    for (int k = 0; k * period < traj.end_s; ++k) {
      TrackedFrame f;
      f.exposure_start_s = k * period;
      f.true_gaze_deg = traj.gazeAt(f.exposure_start_s + oe.exposure_s / 2);
      f.found = true;
      f.confidence = 1;
      f.gaze_deg = {f.true_gaze_deg[0] + noise(rng), f.true_gaze_deg[1] + noise(rng)};
      run.frames.push_back(f);
    }
    run.calibration_precision_sd_deg = o.synthetic_sigma_deg * std::sqrt(2.0);
    return run;
  };
  std::future<TrackedRun> right_run = std::async(std::launch::async, trackEye, 1);
  std::array<TrackedRun, 2> runs;
  runs[0] = trackEye(0);
  runs[1] = right_run.get();
  for (int e = 0; e < 2; ++e) {
    const auto ei = static_cast<std::size_t>(e);
    r.eyes[ei] = simulateStages(*scenes[ei], runs[ei], optionsFor(e));
  }
  // Per-axis sample SD: precision SD is the RMS angle to the mean direction over both axes.
  r.precision_sd_deg_left = runs[0].calibration_precision_sd_deg / std::sqrt(2.0);
  r.precision_sd_deg_right = runs[1].calibration_precision_sd_deg / std::sqrt(2.0);

  // Focus stages, one per eye on its own train (its combiner, its micro-OLED's stage model).
  ClosedLoopOptions of = o.loop;
  if (o.focus_stage_model) of.stage_model = o.focus_stage_model;
  struct FocusAxis {
    apt::StageModel stage;
    double u0 = 0, u_lo = 0, u_hi = 0;
  };
  std::array<FocusAxis, 2> fa;
  std::vector<FollowedAxis> axes;
  for (std::size_t e = 0; e < 2; ++e) {
    FocusEye& fe = r.focus_eyes[e];
    // The train's focus axis (foveal_display z, scene format "stages"), when it has one.
    const StageBinding* axis = nullptr;
    for (const auto& b : scenes[e]->stages)
      if (b.element == "foveal_display" && b.axis == "z") axis = &b;
    ClosedLoopOptions oe = of;
    if (axis && !oe.stage_model) oe.stage_model = axis->stage_model;
    fa[e].stage = stageModelFor(*scenes[e], "foveal_display", oe, fe.stage);
    fe.counts_per_mm = fa[e].stage.counts_per_unit;
    fe.model = focusStageModel(*scenes[e]);
    fe.travel = focusTravel(fe.model, o.near_mm, o.far_mm);
    fa[e].u0 = fe.model.nominal_panel_mm;
    // The stage's mechanical travel, centred on the 30-250 cm panel range (a fixation off
    // axis at 30 cm needs its image plane nearer than 30 cm along z), short of the focal point;
    // with a focus axis, within its soft limits (z = u0 - u: u in [u0 - z_hi, u0 - z_lo]).
    const double mid = 0.5 * (fe.travel.panel_near_mm + fe.travel.panel_far_mm);
    const double half = 0.5 * (fa[e].stage.travel_max - fa[e].stage.travel_min);
    fa[e].u_lo = std::max(0.5 * fe.travel.panel_near_mm, mid - half);
    fa[e].u_hi = std::min(fe.model.focal_length_mm - 0.01, mid + half);
    if (axis) {
      fa[e].u_lo = std::max(fa[e].u_lo, fa[e].u0 - axis->soft_limits[1]);
      fa[e].u_hi = std::min(fa[e].u_hi, fa[e].u0 - axis->soft_limits[0]);
    }
  }
  // Panel distance of eye e for a fixation depth (z from the rotation centres' plane).
  auto panelForDepth = [&](std::size_t e, double depth_mm) {
    return panelForImageDistance(r.focus_eyes[e].model, depth_mm - radii[e]);
  };
  for (std::size_t e = 0; e < 2; ++e) {
    const FocusEye& fe = r.focus_eyes[e];
    const double start_offset = panelForDepth(e, o.start_distance_mm) - fa[e].u0;
    const double deadband_mm = o.focus_deadband_d / std::abs(dioptresPerMm(fe.model, fa[e].u0));
    axes.emplace_back(fa[e].stage.max_velocity, fa[e].stage.max_acceleration, deadband_mm, start_offset);
  }
  r.focus_stage = r.focus_eyes[1].stage;
  r.focus_model = r.focus_eyes[1].model;
  r.travel = r.focus_eyes[1].travel;
  r.focus_counts_per_mm = r.focus_eyes[1].counts_per_mm;

  // Vergence from both trackers -> filter -> focus commands.
  r.to_command_s = r.eyes[1].latency_to_command_s;
  r.vergence_s = o.vergence_s;
  gaze::FixationDistanceFilter filter(o.geometry, o.dynamics, o.filter);
  struct Command {
    double t;
    std::array<double, 2> offset;  // per eye
  };
  std::vector<Command> commands;
  std::vector<double> raw_err, filt_err, sigmas;
  const std::size_t frames = std::min(runs[0].frames.size(), runs[1].frames.size());
  for (std::size_t k = 0; k < frames; ++k) {
    const TrackedFrame& fl = runs[0].frames[k];
    const TrackedFrame& fr = runs[1].frames[k];
    if (!fl.found || !fr.found) continue;
    const auto gl = mirrorGaze(fl.gaze_deg), gr = fr.gaze_deg;
    const gaze::FixationEstimate est = gaze::fixationFromGazes(o.geometry, gl, gr);
    ++r.vergence_samples;
    const gaze::DioptreUncertainty unc =
        gaze::depthDioptreUncertainty(o.geometry, gl, gr, r.precision_sd_deg_left, r.precision_sd_deg_right);
    double d = 0;
    if (est.valid)
      d = 1000.0 / est.depth_mm;
    else
      ++r.vergence_invalid;
    const double t_mid = fl.exposure_start_s + o.loop.exposure_s / 2;
    const double filtered = filter.update(t_mid, d, std::max(unc.sigma_d, 1e-3));
    sigmas.push_back(unc.sigma_d);
    // Noise statistics late in a fixation (its vergence settled: > 4 tau after the onset).
    const FixationSegment& seg = sched->segmentAt(t_mid);
    if (&seg != &sched->start && t_mid - seg.onset_s > 4 * o.dynamics.tau_s + 0.1) {
      const double truth = 1000.0 / sched->pointAt(t_mid).z();
      if (est.valid) raw_err.push_back(d - truth);
      filt_err.push_back(filtered - truth);
    }
    const double depth = filtered > 0 ? 1000.0 / filtered : std::numeric_limits<double>::infinity();
    Command c{fl.exposure_start_s + r.to_command_s + o.vergence_s, {0, 0}};
    for (std::size_t e = 0; e < 2; ++e) {
      const double u = std::isfinite(depth) && depth > radii[e] ? panelForDepth(e, depth) : fa[e].u_hi;
      c.offset[e] = std::clamp(u, fa[e].u_lo, fa[e].u_hi) - fa[e].u0;
    }
    commands.push_back(c);
  }
  r.closed_form_sigma_d_mean = meanSd(sigmas)[0];
  const auto rs = meanSd(raw_err), fs = meanSd(filt_err);
  r.measured_bias_d_raw = rs[0];
  r.measured_sigma_d_raw = rs[1];
  r.measured_sigma_d_filtered = fs[1];

  // Evaluation: focus error per eye against the point the eyes fixate.
  const double step = o.loop.eval_step_s;
  std::size_t next = 0;
  std::vector<double> focus_moves;
  std::array<std::vector<double>, 2> eye_focus_moves;
  for (std::size_t i = 0; i < sched->segments.size(); ++i) {
    const FixationSegment& seg = sched->segments[i];
    const double end = i + 1 < sched->segments.size() ? sched->segments[i + 1].onset_s : sched->end_s;
    FixationOutcome out;
    out.fixation = fixations[i];
    out.onset_s = seg.onset_s;
    out.vergence_change_deg = seg.to_vergence_deg - seg.from_vergence_deg;
    double last_beyond = -1, eye_last_beyond = -1;
    const double target_d = 1000.0 / fixations[i].distance_mm;
    std::array<double, 2> err{0, 0};
    // Start at the first step at or after the onset; the steps run on a global grid.
    for (auto k = static_cast<long long>(std::ceil(seg.onset_s / step - 1e-9));; ++k) {
      const double te = static_cast<double>(k) * step;
      if (te >= end) break;
      while (next < commands.size() && commands[next].t <= te) {
        for (std::size_t e = 0; e < 2; ++e) axes[e].command(commands[next].t, commands[next].offset[e]);
        ++next;
      }
      const Eigen::Vector3d q = sched->pointAt(te);
      for (std::size_t e = 0; e < 2; ++e) {
        const double plane_z = radii[e] + imageDistanceForPanel(r.focus_eyes[e].model, fa[e].u0 + axes[e].position(te));
        const auto g = gaze::gazeTowardsDeg(centres[e], q);
        const Eigen::Vector3d dir = gazeDirection(g[0], g[1]);
        const Eigen::Vector3d pupil = centres[e] + radii[e] * dir;
        const double s_display = (plane_z - pupil.z()) / dir.z();
        err[e] = 1000.0 / s_display - 1000.0 / (q - pupil).norm();
      }
      const double worst = std::max(std::abs(err[0]), std::abs(err[1]));
      out.peak_focus_error_d = std::max(out.peak_focus_error_d, worst);
      if (worst > o.tolerance_d) last_beyond = te;
      if (std::abs(1000.0 / q.norm() - target_d) > o.tolerance_d) eye_last_beyond = te;
      if (te + step >= end) break;
    }
    out.final_focus_error_d = err;
    out.final_focus_error_worst_d = std::abs(err[0]) >= std::abs(err[1]) ? err[0] : err[1];
    if (last_beyond < 0)
      out.time_to_tolerance_s = 0.0;
    else if (last_beyond + step < end - 0.5 * step)
      out.time_to_tolerance_s = last_beyond + step - seg.onset_s;
    if (eye_last_beyond < 0)
      out.eye_time_to_tolerance_s = 0.0;
    else if (eye_last_beyond + step < end - 0.5 * step)
      out.eye_time_to_tolerance_s = eye_last_beyond + step - seg.onset_s;
    // The focus stage's move for this fixation change (trapezoid between the two targets).
    const double depth_from =
        i == 0 ? o.start_distance_mm
               : fixations[i - 1].distance_mm *
                     gazeDirection(fixations[i - 1].direction_deg[0], fixations[i - 1].direction_deg[1]).z();
    const double depth_to =
        fixations[i].distance_mm * gazeDirection(fixations[i].direction_deg[0], fixations[i].direction_deg[1]).z();
    for (std::size_t e = 0; e < 2; ++e) {
      const double move = MotionProfile::trapezoid(0, panelForDepth(e, depth_from), panelForDepth(e, depth_to),
                                                   fa[e].stage.max_velocity, fa[e].stage.max_acceleration)
                              .endTime();
      eye_focus_moves[e].push_back(move);
      out.focus_motion_s = std::max(out.focus_motion_s, move);
    }
    focus_moves.push_back(out.focus_motion_s);
    for (std::size_t e = 0; e < 2; ++e) {
      const auto& er = r.eyes[e];
      if (i < er.off_fovea_per_saccade_s.size() && er.interval_per_saccade_s[i] > 0)
        out.inset_on_fovea_fraction[e] =
            std::clamp(1 - er.off_fovea_per_saccade_s[i] / er.interval_per_saccade_s[i], 0.0, 1.0);
    }
    r.fixations.push_back(out);
  }
  r.focus_move_s = statsOf(focus_moves);
  for (std::size_t e = 0; e < 2; ++e) r.focus_eyes[e].move_s = statsOf(eye_focus_moves[e]);

  // The lateral stages' moves per fixation change (trapezoids between the settled targets, the
  // slower axis), per eye in its own train: the motion part of each path's budget.
  for (std::size_t e = 0; e < 2; ++e) {
    const Scene& scene = *scenes[e];
    const bool mirrored = e == 0;
    const apt::StageModel hoe = stageModelFor(scene, "hoe", o.loop, r.eyes[e].hoe_stage);
    const apt::StageModel oled = stageModelFor(scene, "foveal_display", o.loop, r.eyes[e].oled_stage);
    std::vector<double> hoe_moves, oled_moves;
    for (const auto& seg : sched->segments) {
      const auto from = ownGaze(static_cast<int>(e), seg.onset_s), to = ownGaze(static_cast<int>(e), seg.onset_s + 10);
      const auto h0 = hoeShiftInOwnFrame(scene, from, mirrored), h1 = hoeShiftInOwnFrame(scene, to, mirrored);
      const auto f0 = fovealShiftForGaze(scene, from), f1 = fovealShiftForGaze(scene, to);
      double th = 0, tf = 0;
      for (std::size_t k = 0; k < 2; ++k) {
        th = std::max(th, MotionProfile::trapezoid(0, h0[k], h1[k], hoe.max_velocity, hoe.max_acceleration).endTime());
        tf =
            std::max(tf, MotionProfile::trapezoid(0, f0[k], f1[k], oled.max_velocity, oled.max_acceleration).endTime());
      }
      hoe_moves.push_back(th);
      oled_moves.push_back(tf);
    }
    r.hoe_move_s[e] = statsOf(hoe_moves);
    r.oled_move_s[e] = statsOf(oled_moves);
  }
  return r;
}

}  // namespace fovea::devices
