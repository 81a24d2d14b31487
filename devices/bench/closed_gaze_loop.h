#pragma once
// The closed gaze loop on the virtual bench: eye camera (rendered IR frames,
// model/gaze/eye_image_renderer.h) -> pupil detector -> C.4 gaze map -> stage targets (HOE
// to the pupil-following x_p, micro-OLED to x_f, model/physics/display_camera_map.h) -> stage
// motion (trapezoidal profiles of the scene's stage models, coalesced like
// TargetFollower: while a move runs only the latest target is kept).
//
// The eye makes saccades with fixations between. Saccade amplitudes are uniform in
// [amplitude_min_deg, amplitude_max_deg]; their peak velocities follow the main sequence
// V = 700 (1 - exp(-A / 10 deg)) deg/s (the exponential fit of Baloh et al., "Quantitative
// measurement of saccade amplitude, duration, and velocity", Neurology 1975, with their
// typical constants); the trajectory is minimum-jerk (Flash & Hogan 1985), whose peak velocity
// is 1.875 A / D, so the duration is D = 1.875 A / V (2 deg: 30 ms, 10: 42 ms, 20: 62 ms,
// close to the 2.2 A + 21 ms of Carpenter 1988).
//
// Each stage of the loop is timed: capture (exposure + readout), detect, map, command (USB
// round trip) and the stage motion. The inset error is the angle between the true gaze and
// the gaze the micro-OLED is positioned for (x_f inverted); "off the fovea" is an error
// beyond the eye's fovea radius. FOV loss while the HOE is in transit: the peripheral image
// is a Maxwellian view, every field angle passing through the projector's focus (exit-pupil
// disc) at the pupil; a HOE position error moves that focus by the same amount across the
// pupil (the shift x_p follows the pupil one to one), and the fraction of the focus
// outside the pupil (circle-circle overlap) is the fraction of the field's light lost. The
// field is lost entirely when the focus leaves the pupil.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "devices/apt/stage_models.h"
#include "model/gaze/eye_image_renderer.h"
#include "model/gaze/gaze_calibration.h"
#include "model/gaze/pupil_detector_choice.h"
#include "model/scene/scene.h"

namespace fovea::devices {

struct ClosedLoopOptions {
  int saccades = 10;
  std::uint32_t seed = 1;
  double camera_fps = 120;
  double exposure_s = 0.004, readout_s = 0.002;
  double detect_s = 0.002;  // modelled detector time (the measured one is reported beside it)
  double map_s = 0.00005, command_s = 0.001;
  double extra_latency_s = 0;              // added between detection and command (the latency sweep)
  std::optional<std::string> stage_model;  // override the scene's stage models ("DDSM50", ...)
  double deadband_mm = 0.01;
  double min_confidence = 0.5;
  double settle_tolerance_deg = 1.0;
  double fixation_min_s = 0.15, fixation_max_s = 0.4;
  double amplitude_min_deg = 2, amplitude_max_deg = 20;
  double eval_step_s = 0.0005;
  gaze::IrCameraPose camera;
  int leds = 6;
  gaze::PupilDetectorKind detector = gaze::PupilDetectorKind::Classical;  // of the calibration and the loop
  // The scene is a left eye's train in the bench frame (eye_scene.h) while gazes and stage
  // targets are in the eye's own, mirrored, frame (the binocular loop's left eye): the HOE's
  // x_p is then mirrorHoeShift's (below). False: scene and gazes share the frame.
  bool mirrored_frame = false;
};

// The geometric HOE shift x_p for a gaze in the eye's own frame (o.mirrored_frame: the
// scene's train is a left eye's in the bench frame, the gaze its own mirrored one). Under the
// mirror S = diag(-1, 1, 1) a gaze (yaw, pitch) is (-yaw, pitch) in the bench frame, and the
// HOE's local x is reversed (eye_scene.h), so x_p_own(yaw, pitch) = (-x, y) of
// geometricHoeShiftForGaze(scene, (-yaw, pitch)).
std::array<double, 2> hoeShiftInOwnFrame(const Scene& scene, std::array<double, 2> gaze_deg, bool mirrored_frame);

// The measured side of the loop: one entry per camera frame.
struct TrackedFrame {
  double exposure_start_s = 0;
  std::array<double, 2> true_gaze_deg{0, 0};  // mid-exposure
  bool found = false;
  double confidence = 0;
  std::array<double, 2> gaze_deg{0, 0};  // mapped estimate (when found)
  double detect_wall_s = 0;              // measured detector time
};

struct SaccadeEvent {
  double onset_s = 0, duration_s = 0, amplitude_deg = 0, peak_velocity_deg_s = 0;
  std::array<double, 2> from_deg{0, 0}, to_deg{0, 0};
};

struct EyeTrajectory {
  std::vector<SaccadeEvent> saccades;
  double end_s = 0;
  // When set, the gaze at a time (the binocular loop's eyes, which also verge); `saccades`
  // then only marks the onsets for the per-saccade statistics.
  std::function<std::array<double, 2>(double)> path;
  std::array<double, 2> gazeAt(double t_s) const;
};
// Main-sequence peak velocity (deg/s) and minimum-jerk duration (s) of a saccade.
double mainSequencePeakVelocity(double amplitude_deg);
double saccadeDuration(double amplitude_deg);
EyeTrajectory makeSaccadeTrajectory(const Scene& scene, const ClosedLoopOptions& o);

struct Stats {
  double mean = 0, p95 = 0, max = 0;
  std::size_t count = 0;  // 0: no values (the statistics are meaningless)
};
Stats statsOf(std::vector<double> v);

struct ClosedLoopResult {
  double capture_s = 0, detect_s = 0, detect_measured_mean_s = 0, detect_measured_max_s = 0, map_s = 0, command_s = 0,
         extra_latency_s = 0;
  double latency_to_command_s = 0;    // exposure start to command sent
  Stats hoe_move_s, oled_move_s;      // per saccade: command to arrival of the last move it caused
  std::string hoe_stage, oled_stage;  // stage models used
  Stats inset_error_deg;              // over time
  double time_off_fovea_s = 0, time_beyond_tolerance_s = 0, duration_s = 0;
  Stats settle_s;      // per saccade that settles: onset to the inset staying within tolerance
  int unsettled = 0;   // saccades after which the inset had not settled when the next one began
  Stats hoe_error_mm;  // focus displacement across the pupil
  double fov_partly_lost_s = 0, fov_lost_s = 0, mean_light_lost = 0;
  int frames = 0, frames_found = 0;
  double calibration_accuracy_deg = 0, calibration_precision_deg = 0;
  std::vector<SaccadeEvent> saccades;
  // Per saccade: time off the fovea and length of the interval from its onset to the next
  // onset (or the end).
  std::vector<double> off_fovea_per_saccade_s, interval_per_saccade_s;
};

// Renders and tracks the frames of a trajectory (the expensive part, run once).
struct TrackedRun {
  EyeTrajectory trajectory;
  std::vector<TrackedFrame> frames;
  double calibration_accuracy_deg = 0, calibration_precision_deg = 0, calibration_precision_sd_deg = 0;
};
TrackedRun trackTrajectory(const Scene& scene, const ClosedLoopOptions& o);
// The same for a given trajectory (calibration and frames seeded by o.seed).
TrackedRun trackEyeTrajectory(const Scene& scene, const ClosedLoopOptions& o, EyeTrajectory trajectory);
// The stage model of `element`'s lateral axes (o.stage_model, else the scene's, else
// MTS25-Z8); `name` receives it. Throws std::invalid_argument for an unknown model.
apt::StageModel stageModelFor(const Scene& scene, const std::string& element, const ClosedLoopOptions& o,
                              std::string& name);
// Drives the stages from a tracked run and measures the inset error and FOV loss.
// Throws std::invalid_argument for an unknown stage model.
ClosedLoopResult simulateStages(const Scene& scene, const TrackedRun& run, const ClosedLoopOptions& o);

}  // namespace fovea::devices
