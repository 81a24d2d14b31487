#pragma once
// The binocular closed loop with focus (issue 30): two eyes fixating points in depth
// (30-250 cm) and direction; per eye the monocular closed gaze loop of closed_gaze_loop.h
// (eye camera frames -> pupil detector -> C.4 calibration -> HOE and micro-OLED stages),
// each eye on its own optical train (eye_scene.h: the left train is the mirror image of the
// scene's, or in mode "explicit" the file's own left train); from both tracked
// gazes the fixation point (model/gaze/vergence.h: closest approach, closed-form
// uncertainty, fixation-distance filter) drives one focus stage per eye, which moves the
// micro-OLED along the combiner's axis (model/physics/focus_stage.h).
//
// Frames. Head frame of vergence.h (x towards the right eye, the eyes' rotation centres at
// -+ipd/2 on x). Each eye's monocular loop runs in the eye's own frame, the right eye's
// train's; the left eye's own frame is the mirror image of the bench frame (its gaze
// (yaw, pitch) is (-yaw, pitch) in the bench frame, its stages move mirrored), so its tracker,
// calibration and stage targets are those of a right eye (ClosedLoopOptions::mirrored_frame:
// only the HOE's x_p reads the left train's bench geometry). Per eye from its own train: the
// HOE and micro-OLED stage models, x_p and x_f, the eye (pupil, fovea, eyeball radius), the
// combiner (the focus stage model) and the focus stage's model; the rotation centres come
// from the IPD. Both eye cameras expose at the same instants.
//
// The eyes. Fixation i (point P_i at cyclopean distance d_i in direction u_i) starts at
// onset t_i: the direction changes by a main-sequence minimum-jerk saccade (as the monocular
// loop), the vergence angle (of the straight-ahead point at the same distance) by the
// rate-limited first-order response of vergence.h; the eyes fixate Q(t) = u(t) dist(gamma(t)),
// each eye's gaze is the exact line of sight to Q(t). Time is measured from the onset of the
// eyes' movement: the ~160 ms from a stimulus to that onset precede any eye signal and are
// outside the display's loop (reported as `eye_vergence_latency`).
//
// Focus error (per eye, dioptres): 1000 / (distance along the eye's line of sight from its
// pupil to the foveal image plane) - 1000 / |Q(t) - pupil|: the display against where the
// eye fixates now (accommodation is driven with vergence). The image plane is the focus
// stage's: z = eyeball radius + d(u) in the head frame (d from the zero-gaze pupil).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "devices/bench/closed_gaze_loop.h"
#include "model/gaze/vergence.h"
#include "model/physics/focus_stage.h"
#include "model/scene/scene.h"

namespace fovea::devices {

struct BinocularFixation {
  double distance_mm = 800;                   // cyclopean distance of the point
  std::array<double, 2> direction_deg{0, 0};  // cyclopean direction (yaw, pitch), Fick
  double hold_s = 1.0;                        // until the next fixation's onset
};

struct BinocularOptions {
  ClosedLoopOptions loop;  // per eye (seed ignored: seed_left / seed_right)
  std::uint32_t seed_left = 2, seed_right = 1;
  gaze::BinocularGeometry geometry;
  gaze::VergenceDynamics dynamics;
  gaze::FixationFilterOptions filter;
  // Default: the train's focus axis's model (foveal_display z), else the micro-OLED's lateral
  // stage model (loop.stage_model overrides both); with a focus axis the commands stay within its
  // soft limits.
  std::optional<std::string> focus_stage_model;
  double start_distance_mm = 800, start_hold_s = 0.3;
  double vergence_s = 0.00001;          // modelled closest approach + filter time
  double focus_deadband_d = 0.02;       // focus commands within this of the last one are dropped
  double near_mm = 300, far_mm = 2500;  // focus range (seed C.3), from the pupil
  double tolerance_d = 0.25;
  bool track = true;                  // false: the trackers' gaze is the truth plus Gaussian noise (no rendering)
  double synthetic_sigma_deg = 0.05;  // per axis, when track is false
};

// Fixations drawn with `seed`: distance uniform in dioptres over [near, far], direction
// uniform in yaw [-12, 12] x pitch [-8, 8] deg, hold 0.8-1.4 s.
std::vector<BinocularFixation> randomFixations(int n, std::uint32_t seed, double near_mm = 300, double far_mm = 2500);

struct FixationOutcome {
  BinocularFixation fixation;
  double onset_s = 0;
  std::optional<double> time_to_tolerance_s;        // onset to the focus error staying within tolerance
  std::optional<double> eye_time_to_tolerance_s;    // the eyes' own vergence to within tolerance of the target
  std::array<double, 2> final_focus_error_d{0, 0};  // left, right, at the end of the fixation
  double final_focus_error_worst_d = 0;             // the larger in magnitude, signed
  std::array<double, 2> inset_on_fovea_fraction{0, 0};
  double peak_focus_error_d = 0;
  double focus_motion_s = 0;  // the focus stages' move between the previous and this target (the slower eye)
  double vergence_change_deg = 0;
};

// One eye's focus stage.
struct FocusEye {
  std::string stage;  // stage model
  FocusStageModel model;
  FocusTravel travel;
  double counts_per_mm = 0;
  Stats move_s;  // per fixation change
};

struct BinocularResult {
  std::vector<FixationOutcome> fixations;
  std::array<ClosedLoopResult, 2> eyes;  // left, right (each in its own frame, the left one mirrored)
  std::array<FocusEye, 2> focus_eyes;    // left, right
  // The right eye's focus stage (focus_eyes[1]; both eyes' in mode "mirror").
  std::string focus_stage;
  FocusStageModel focus_model;
  FocusTravel travel;
  double focus_counts_per_mm = 0;
  double to_command_s = 0, vergence_s = 0;
  Stats focus_move_s;                            // per fixation change: the focus stage's move
  std::array<Stats, 2> hoe_move_s, oled_move_s;  // the same for each eye's lateral stages
  int vergence_samples = 0, vergence_invalid = 0;
  double precision_sd_deg_left = 0, precision_sd_deg_right = 0;                             // per-axis sample SD used
  double closed_form_sigma_d_mean = 0;                                                      // over the samples
  double measured_sigma_d_raw = 0, measured_sigma_d_filtered = 0, measured_bias_d_raw = 0;  // late in each fixation
  double duration_s = 0;
};

// Runs the loop on the two eyes' monocular scenes, both in the bench frame (eyeScene(scene,
// EyeSide::Left|Right)); the trackers render every frame unless o.track is false. Throws
// std::invalid_argument for an unknown stage model or an empty fixation list.
BinocularResult runBinocularLoop(const Scene& left, const Scene& right, const std::vector<BinocularFixation>& fixations,
                                 const BinocularOptions& o);
// The same for one scene: a binocular scene's two eyes (eye_scene.h), or a monocular scene as
// the right eye with its mirror image o.geometry.ipd_mm / 2 nasal of its rotation centre as the left.
BinocularResult runBinocularLoop(const Scene& scene, const std::vector<BinocularFixation>& fixations,
                                 const BinocularOptions& o);

}  // namespace fovea::devices
