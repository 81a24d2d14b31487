#pragma once
// A wider synthetic eye domain than the pupil benchmark's (pupil_benchmark.h), for training
// and testing a detector on eyes it was not tuned on (domain randomisation: Tobin et al.,
// "Domain randomization for transferring deep neural networks from simulation to the real
// world", IROS 2017; NVGaze, Kim et al. CHI 2019, trains its pupil network the same way).
// Randomised per frame: lid shapes and occlusion up to 70 % of the pupil, lashes (0-120),
// iris texture and grey levels, corneal refraction of the pupil (the entrance pupil), camera
// views up to 45 deg off the optical axis, glints of LED rings and stray glints anywhere
// (on the pupil edge too), saccadic motion blur, defocus, sensor noise, gain and offset
// (dim to saturated), an illumination gradient, soft shadows and partial frames (the pupil
// near or across the frame edge).
//
// Held-out subsets (never seen by training): their seed sequence carries the subset's id,
// so no seed gives a training frame, and they draw the pupil diameter and iris level from
// bands the training set excludes (4.5-5.0 mm, 0.38-0.46). Subsets: easy, glints,
// occlusion (30-90 % visible), motion_blur, off_axis (20-45 deg), partial, hard (30-50 %
// visible, glints and blur together) and closed (no pupil: false positives).
// Deterministic by (subset, index, seed). Ground truth as eye_image_renderer.h; a partial
// frame's visible_fraction also leaves out the part outside the frame.
//
// Training subsets (the training's pupil diameter and iris level bands): train, the whole
// domain, and train_hard, the hard subset's combination (LED and stray glints, defocus, 70 %
// motion blur, 25 % off-axis views) at 20-65 % visible, and train_partial, train's draws with
// every frame partial (the pupil's centre within a radius of a frame edge; train has 12 %).
// Of train's frames 12 % show 20-65 % of the pupil, 3.6 % of them with both kinds of glints
// too, 1.1 % with saccadic blur as well.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/gaze/eye_image_renderer.h"

namespace fovea::gaze {

// New subsets go last: a subset's number seeds its frames, so the others' frames stay as they
// were; allWideSubsets counts up to the last one.
enum class WideSubset {
  Train,
  Easy,
  Glints,
  Occlusion,
  MotionBlur,
  OffAxis,
  Partial,
  Hard,
  Closed,
  TrainHard,
  TrainPartial
};

const char* wideSubsetName(WideSubset s);
std::vector<WideSubset> allWideSubsets();  // in the enum's order
std::optional<WideSubset> parseWideSubset(const std::string& name);
// Train, TrainHard and TrainPartial: drawn from the training's bands, never held out.
bool isTrainingWideSubset(WideSubset s);
std::vector<WideSubset> heldOutWideSubsets();  // the others, in the enum's order

EyeFrame renderWideFrame(WideSubset subset, int index, std::uint32_t seed);

}  // namespace fovea::gaze
