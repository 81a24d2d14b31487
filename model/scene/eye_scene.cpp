#include "model/scene/eye_scene.h"

#include <stdexcept>
#include <utility>

#include "model/gaze/fixation_gazes.h"

namespace fovea {

namespace {

// The reflection rules of eye_scene.h, one per kind of quantity. Negation as 0 - v, so a
// zero stays +0 (not -0, which a saved scene or a JSON document would print as "-0.0").
double negated(double v) {
  return 0.0 - v;
}
double mirrorX(double x_mm, double mid_plane_x_mm) {
  return 2.0 * mid_plane_x_mm - x_mm;
}
void mirrorPoint(Vec3mm& p, double mid_plane_x_mm) {
  p[0] = mirrorX(p[0], mid_plane_x_mm);
}
void mirrorPose(Pose& pose, double mid_plane_x_mm) {
  mirrorPoint(pose.position_mm, mid_plane_x_mm);
  pose.rotation_deg[0] = negated(pose.rotation_deg[0]);  // yaw
  pose.rotation_deg[2] = negated(pose.rotation_deg[2]);  // roll; pitch is unchanged
}
// An interval of a mirrored coordinate: [a, b] -> [-b, -a].
void mirrorInterval(std::array<double, 2>& interval) {
  interval = {negated(interval[1]), negated(interval[0])};
}
bool flipsUnderMirror(const std::string& axis) {
  return axis == "x" || axis == "yaw" || axis == "roll";
}

}  // namespace

const char* eyeSideName(EyeSide side) {
  return side == EyeSide::Left ? "left" : "right";
}

std::optional<EyeSide> eyeSideFromName(const std::string& name) {
  if (name == "left") return EyeSide::Left;
  if (name == "right") return EyeSide::Right;
  return std::nullopt;
}

double midPlaneX(const Scene& scene) {
  if (!scene.binocular) throw std::invalid_argument("the scene has no binocular block (a monocular scene)");
  const double centre_x_mm = scene.hoe.pose.position_mm[0] + scene.eye.lateral_offset_mm[0];
  return centre_x_mm - scene.binocular->ipd_mm / 2.0;
}

Scene mirroredScene(const Scene& scene, double mid_plane_x_mm) {
  Scene m = scene;
  mirrorPose(m.projector.pose, mid_plane_x_mm);
  mirrorPose(m.hoe.pose, mid_plane_x_mm);
  for (HoeLayer& layer : m.hoe_layers) {
    mirrorPoint(layer.recording.reference_point_mm, mid_plane_x_mm);
    mirrorPoint(layer.recording.signal_point_mm, mid_plane_x_mm);
  }
  // The eye's placement is an offset from the HOE centre (a vector); its gaze a direction.
  m.eye.lateral_offset_mm[0] = negated(m.eye.lateral_offset_mm[0]);
  m.eye.gaze_deg[0] = negated(m.eye.gaze_deg[0]);
  mirrorInterval(m.eye.gaze_range_deg);
  mirrorPose(m.foveal_display.pose, mid_plane_x_mm);
  mirrorPose(m.lens.pose, mid_plane_x_mm);
  for (StageBinding& stage : m.stages) {
    if (!flipsUnderMirror(stage.axis)) continue;
    // The same stage, mounted the same way, over the mirrored element range: its readings
    // element - home_offset keep the interval [a - h, b - h] when the range [a, b] becomes
    // [-b, -a], so h' = h - (a + b) (= h for a range centred on 0).
    const double a = stage.soft_limits[0], b = stage.soft_limits[1];
    mirrorInterval(stage.soft_limits);
    stage.home_offset -= a + b;
  }
  return m;
}

namespace {

// The scene with its train replaced by `t` (mode "explicit"): the left train's unknown keys
// (kept under /binocular/left/...) become the eye scene's own, the right train's are dropped.
Scene withTrain(const Scene& scene, const OpticalTrain& t) {
  Scene out = scene;
  out.projector = t.projector;
  out.hoe = t.hoe;
  out.hoe_layers = t.hoe_layers;
  out.eye = t.eye;
  out.foveal_display = t.foveal_display;
  out.lens = t.lens;
  out.foveation = t.foveation;
  out.stages = t.stages;
  const std::string left = "/binocular/left";
  nlohmann::ordered_json unknown = nlohmann::ordered_json::object();
  for (auto it = scene.unknown.begin(); it != scene.unknown.end(); ++it) {
    const std::string& pointer = it.key();
    if (pointer.rfind(left + "/", 0) == 0)
      unknown[pointer.substr(left.size())] = it.value();
    else if (pointer == left || pointer == "/" || pointer.rfind("/view", 0) == 0)  // the root, not a train's
      for (auto kv = it->begin(); kv != it->end(); ++kv)
        unknown[pointer == left ? "/" : pointer][kv.key()] = kv.value();
  }
  out.unknown = std::move(unknown);
  return out;
}

}  // namespace

Scene eyeScene(const Scene& scene, EyeSide side) {
  const double mid_plane_x_mm = midPlaneX(scene);  // throws for a monocular scene
  Scene eye = side == EyeSide::Right  ? scene
              : scene.binocular->left ? withTrain(scene, *scene.binocular->left)
                                      : mirroredScene(scene, mid_plane_x_mm);
  // A fixation distance: the left eye fixates the point on the right eye's line of sight (the
  // bench frame and the head frame share their axes; the head frame's origin is the
  // mid-plane point level with the right eye's rotation centre, whose offset cancels in the
  // gaze directions).
  if (side == EyeSide::Left && scene.binocular->fixation_distance_mm > scene.binocular->ipd_mm / 2)
    eye.eye.gaze_deg = gaze::fixationOnRightGaze(gaze::BinocularGeometry{scene.binocular->ipd_mm}, scene.eye.gaze_deg,
                                                 scene.binocular->fixation_distance_mm)
                           .left_deg;
  eye.binocular.reset();
  return eye;
}

std::array<double, 2> leftGazeDeg(const Scene& scene) {
  return eyeScene(scene, EyeSide::Left).eye.gaze_deg;
}

Scene explicitBinocularScene(const Scene& scene) {
  const Scene left = eyeScene(scene, EyeSide::Left);  // throws for a monocular scene
  Scene out = scene;
  out.binocular->mode = "explicit";
  out.binocular->left = OpticalTrain{left.projector,      left.hoe,  left.hoe_layers, left.eye,
                                     left.foveal_display, left.lens, left.foveation,  left.stages};
  return out;
}

}  // namespace fovea
