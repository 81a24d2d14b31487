#pragma once
// One eye of a binocular scene as a monocular scene (issue 30).
//
// A binocular scene (scene.h, "binocular" block) holds one optical train, the right eye's, in
// the bench frame (+x temporal for the right eye); mode "explicit" also holds the left eye's
// train as written. In mode "mirror" the left train is the right one's mirror image about
// the head's mid-sagittal plane x = x_m, which lies half the interpupillary distance nasal of
// the right eye's rotation centre c_x (scene_geometry.h placeEye):
//   x_m = c_x - ipd_mm / 2,   c_x = hoe.position_mm[0] + eye.lateral_offset_mm[0].
// The reflection S = diag(-1, 1, 1) about that plane maps
//   a point       (x, y, z) -> (2 x_m - x, y, z),
//   a vector      (x, y, z) -> (-x, y, z)  (offsets relative to another element: lateral offsets),
//   a rotation    R -> S R S; with R = Ry(yaw) Rx(-pitch) Rz(roll) and S Ry(a) S = Ry(-a),
//                 S Rx(a) S = Rx(a), S Rz(a) S = Rz(-a): (yaw, pitch, roll) -> (-yaw, pitch, -roll).
//                 The new local axes S R S e_i are the mirror images S (R e_i) of the old ones
//                 except local x, which is reversed (-S R e_x) to keep the frame right-handed:
//                 a point at local (u, v, w) of the right element is at (-u, v, w) of the left
//                 one (an HOE shift or a plate point in local x changes sign, a projector
//                 pixel column is mirrored),
//   a gaze        (yaw, pitch) -> (-yaw, pitch)  (a yaw turns +z towards +x),
//   a stage axis  x, yaw, roll: the element's range mirrored (soft limits [a, b] -> [-b, -a]);
//                 the stage itself is the same one mounted the same way (a reading still
//                 grows towards +x), covering the same readings: home_offset h -> h - (a + b)
//                 (unchanged for limits centred on 0); y, z, pitch axes unchanged.
// Everything else (sizes, indices, wavelengths, the combiner, the foveation) is the same for
// both eyes. Both eyes' scenes stay in the one bench frame, so the two trains can be drawn
// together and the left eye's rotation centre lies at c_x - ipd_mm.
//
// Pure functions of the scene: no I/O, no state.

#include <array>
#include <optional>
#include <string>

#include "model/scene/scene.h"

namespace fovea {

enum class EyeSide { Left, Right };

// "left" / "right".
const char* eyeSideName(EyeSide side);
// Parses "left" / "right"; nullopt otherwise.
std::optional<EyeSide> eyeSideFromName(const std::string& name);

// The mid-sagittal plane's x in the bench frame (x_m above); requires scene.binocular.
double midPlaneX(const Scene& scene);

// The monocular scene of one eye of a binocular scene: the right eye's is the scene without
// its "binocular" block, the left eye's its mirror image (above) or, in mode "explicit", the
// scene with the block's left train in place of its own, also without the block.
// Throws std::invalid_argument when the scene has no "binocular" block.
Scene eyeScene(const Scene& scene, EyeSide side);

// The left eye's gaze (degrees, bench frame): the mirror of the right eye's in mode "mirror",
// the left train's own in mode "explicit", and with binocular.fixation_distance_mm set the
// gaze fixating the point at that distance on the right eye's line of sight
// (model/gaze/fixation_gazes.h fixationOnRightGaze). Throws for a monocular scene.
std::array<double, 2> leftGazeDeg(const Scene& scene);

// The binocular scene in mode "explicit" whose left train is its left eye's train now (the
// mirror image for mode "mirror"): the same eyes, the left one written out. Throws
// std::invalid_argument for a monocular scene.
Scene explicitBinocularScene(const Scene& scene);

// The mirror image of `scene` about the plane x = mid_plane_x_mm (the rules above); the
// binocular block, notes and unknown keys are kept as they are.
Scene mirroredScene(const Scene& scene, double mid_plane_x_mm);

}  // namespace fovea
