#pragma once
// The bench: every optical element of the foveated AR display, as plain structs.
//
// Frame and units (docs/scene-format.md): the bench frame is right-handed, in mm.
//   +x  lateral, towards the projector's side (temporal for a right eye),
//   +y  up,
//   +z  forward: from the eye towards the HOE and the world (the line of sight at zero gaze).
// The origin is free; the prototype puts the HOE centre at the origin.
// Every element has a Pose: a position and three rotations (yaw about +y, then pitch about
// the rotated +x, then roll about the rotated +z). An element's local +z is its optical
// axis: the projector's emission direction, the HOE film normal pointing to the eye side
// (−z of the bench at zero rotation, see hoeNormal()), the micro-OLED's emission direction.
//
// Values carry their unit in the member name (_mm, _deg, _nm, _um). Angles in degrees.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fovea {

using Vec3mm = std::array<double, 3>;

struct Pose {
  Vec3mm position_mm{0.0, 0.0, 0.0};
  // yaw (about +y), pitch (about rotated +x), roll (about rotated +z), degrees.
  std::array<double, 3> rotation_deg{0.0, 0.0, 0.0};
  bool operator==(const Pose&) const = default;
};

// A.2.1 / Fig. S3: each scanned pixel reaches a waist a short way out of the projector and
// then grows linearly with throw; elliptical near the exit, round far away.
struct PixelBeamModel {
  double waist_distance_mm = 150.0;  // throw at which the pixel is smallest (Fig. S3: ~0.15 m)
  double waist_fwhm_um = 600.0;      // FWHM at the waist
  double divergence_mrad = 1.2;      // full-angle FWHM growth rate after the waist
  double exit_fwhm_um = 1200.0;      // FWHM at the exit pupil (long axis)
  double exit_ellipticity = 1.6;     // long/short axis ratio at the exit; -> 1 far away
  bool operator==(const PixelBeamModel&) const = default;
};

struct Projector {
  std::string name = "projector";
  Pose pose;
  std::array<int, 2> pixels{1280, 720};       // horizontal, vertical
  std::array<double, 2> fov_deg{40.0, 22.5};  // full horizontal, vertical projection angles
  std::vector<double> wavelengths_nm{660.0, 532.0, 460.0};
  double exit_pupil_diameter_mm = 1.0;
  PixelBeamModel pixel_beam;
  bool operator==(const Projector&) const = default;
};

// The HOE carrier: one rigid plate (the stack of layers), moved by the stages.
struct Hoe {
  std::string name = "hoe";
  Pose pose;                                  // centre of the stack; local +z = film normal
  std::array<double, 2> size_mm{40.0, 30.0};  // width (local x), height (local y)
  double substrate_thickness_mm = 0.0;        // glass behind the films (0 = film only)
  double cover_index = 1.0;                   // medium on the eye side of the stack
  double substrate_index = 1.0;               // medium on the world side of the stack
  bool operator==(const Hoe&) const = default;
};

// How one layer was recorded (B.1). The two construction points are in bench coordinates
// with the HOE at its nominal pose (recorded in place); the fringes then move with the HOE.
struct HoeRecording {
  double wavelength_nm = 532.0;
  Vec3mm reference_point_mm{0.0, 0.0, 0.0};  // diverging reference source (the projector)
  Vec3mm signal_point_mm{0.0, 0.0, -22.0};   // converging signal focus (the pupil centre)
  bool phase_conjugate = false;              // B.1.2: record with the time-reversed pair
  bool operator==(const HoeRecording&) const = default;
};

struct HoeLayer {
  std::string name;  // "red", "green", "blue", ...
  double thickness_um = 16.0;
  double offset_um = 0.0;          // layer centre along the normal from the stack centre
  double n0 = 1.5;                 // mean index of the processed film
  double n1 = 0.02;                // index modulation amplitude
  double absorption_per_mm = 0.0;  // intensity absorption coefficient alpha (1/mm)
  // Processing changes: the film shrinks along its normal (negative = thinner) and its mean
  // index moves by delta_n0 relative to the index during recording.
  double shrinkage_percent = 0.0;
  double recording_n0_delta = 0.0;  // n0(recording) = n0 - recording_n0_delta
  HoeRecording recording;
  bool operator==(const HoeLayer&) const = default;
};

struct Eye {
  double eyeball_diameter_mm = 23.0;
  double pupil_diameter_mm = 5.0;
  // Eye relief: distance along the bench z axis from the pupil centre (at zero gaze) to the
  // HOE centre. The eye's rotation centre sits eyeball_radius behind the pupil.
  double relief_mm = 22.0;
  std::array<double, 2> lateral_offset_mm{0.0, 0.0};  // decentration (x, y) of the eye
  std::array<double, 2> gaze_deg{0.0, 0.0};           // yaw (+ towards +x), pitch (+ up)
  std::array<double, 2> gaze_range_deg{-20.0, 20.0};  // design range of gaze angles
  double fovea_radius_deg = 5.0;                      // foveal region served by the micro-OLED
  bool operator==(const Eye&) const = default;
};

// The seed's foveal path (A.5.1, Fig. S9): micro-OLED imaged by an on-axis magnifier
// combiner to a virtual image at image_distance_mm, moved by a stage by x_f (Eq. S1).
struct ImageCombiner {
  std::string name = "IC2";
  double magnification = 10.0;               // M: lateral magnification display -> virtual image
  double eye_distance_mm = 22.0;             // b: combiner (eye-side principal plane) to pupil
  double image_distance_mm = 800.0;          // d_f: virtual image distance from the eye
  double mtf30_cpd_on_axis = 60.0;           // optical limit on axis (Fig. S7)
  double field_curvature_per_deg2 = 0.0015;  // fractional MTF30 drop per deg^2 off-axis
  bool operator==(const ImageCombiner&) const = default;
};

struct FovealDisplay {
  std::string name = "micro-OLED";
  Pose pose;
  std::array<double, 2> size_mm{15.36, 8.64};  // active area
  std::array<int, 2> pixels{1920, 1080};
  std::vector<double> primaries_nm{620.0, 530.0, 460.0};
  ImageCombiner combiner;
  bool operator==(const FovealDisplay&) const = default;
};

struct BeamShapingLens {
  bool enabled = false;
  std::string name = "beam-shaping lens";
  Pose pose;
  double focal_length_mm = 50.0;
  double diameter_mm = 12.7;
  double center_thickness_mm = 3.0;
  double index = 1.517;  // N-BK7 at ~550 nm
  bool operator==(const BeamShapingLens&) const = default;
};

// B.2.3: blur ramps from blur_start to blend_start; intensity crossfade to blend_end.
struct Foveation {
  double blur_start_deg = 3.0;   // eps_s
  double blend_start_deg = 5.0;  // eps_o
  double blend_end_deg = 6.0;    // eps_e
  bool operator==(const Foveation&) const = default;
};

// Controller parameters written on connect (0 or "": leave the controller's own). Units:
// the axis's (mm or deg) per s, per s^2.
struct StageControllerSetup {
  double max_velocity = 0, acceleration = 0, jog_step = 0, home_velocity = 0;
  std::string limit_switches;  // "", "ignore", "makes" (switch closes on contact), "breaks"
  bool operator==(const StageControllerSetup&) const = default;
};

// Which motorised axis drives which element coordinate (the live bench, docs/bench.md).
struct StageBinding {
  std::string element;      // "hoe", "foveal_display", "projector", "lens", "camera"
  std::string axis;         // "x", "y", "z" (translation, mm) or "yaw" (rotation, deg)
  std::string controller;   // "KDC101", "TDC001", "KBD101", "K10CR1"
  std::string stage_model;  // "MTS25-Z8", "Z825B", "DDSM50", "K10CR1"
  std::string serial;       // empty: any / virtual
  int channel = 1;
  std::array<double, 2> soft_limits{-10.0, 10.0};  // mm or deg, in the element axis
  double home_offset = 0.0;                        // element coordinate when the stage reads 0
  double counts_per_unit = 0.0;                    // encoder counts per mm (deg); 0: the stage model's figure
  StageControllerSetup setup;
  bool operator==(const StageBinding&) const = default;
};

// View state that changes results, saved with the scene (written only when not default, so
// older files and older studios are unaffected).
struct ViewState {
  bool hoe_follows_gaze = false;  // the HOE travels by x_p(alpha), the FOV-maximising shift (A.4)
  // How x_p is chosen (model/analysis/gaze_studies.h XpRule): "plateau-middle" or "follow-focus".
  std::string xp_rule = "plateau-middle";
  bool operator==(const ViewState&) const = default;
};

// One eye's optical train: the elements of a scene that belong to one eye (binocular mode
// "explicit" holds the left eye's this way; the scene's own are the right eye's).
struct OpticalTrain {
  Projector projector;
  Hoe hoe;
  std::vector<HoeLayer> hoe_layers;
  Eye eye;
  FovealDisplay foveal_display;
  BeamShapingLens lens;
  Foveation foveation;
  std::vector<StageBinding> stages;
  bool operator==(const OpticalTrain&) const = default;
};

// A binocular scene (optional top-level "binocular" block, format version 2). The scene's own
// optical train is the right eye's (+x is temporal for a right eye, above). Mode "mirror": the
// left train is its mirror image about the head's mid-sagittal plane, which lies ipd_mm / 2
// nasal (towards -x) of the right eye's rotation centre (model/scene/eye_scene.h). Mode
// "explicit": the left train is `left`, as written in the file (bench frame), with the same
// elements as the scene's (as many HOE layers, the same stage axes).
struct Binocular {
  std::string mode = "mirror";       // "mirror" or "explicit"
  double ipd_mm = 63.0;              // interpupillary distance (adult mean, Dodgson 2004)
  std::optional<OpticalTrain> left;  // mode "explicit" only: the left eye's train
  // Issue 30 item 5: 0 (off) or the cyclopean distance (mm, from midway between the rotation
  // centres) of the point both eyes fixate on the right eye's line of sight (eye.gaze_deg);
  // the left eye's gaze is then the one fixating it (model/gaze/fixation_gazes.h), not the
  // mirror of the right one's. Applied when it exceeds ipd_mm / 2.
  double fixation_distance_mm = 0;
  bool operator==(const Binocular&) const = default;
};

struct Scene {
  // Files without a "binocular" block are written as version 1 (as before it existed), files
  // with one as version 2; this version reads both.
  static constexpr int kFormatVersion = 2;
  static constexpr int kMonocularFormatVersion = 1;
  std::string name = "untitled";
  nlohmann::ordered_json notes;  // free text / object; kept verbatim
  Projector projector;
  Hoe hoe;
  std::vector<HoeLayer> hoe_layers;
  Eye eye;
  FovealDisplay foveal_display;
  BeamShapingLens lens;
  Foveation foveation;
  std::vector<StageBinding> stages;
  ViewState view;
  std::optional<Binocular> binocular;  // absent: a monocular scene (one eye)
  // Keys this version does not know, by JSON pointer of their parent object, kept so a
  // load -> save round trip loses nothing ("/" is the root, "/eye" the eye object, ...).
  nlohmann::ordered_json unknown = nlohmann::ordered_json::object();

  bool operator==(const Scene&) const = default;
};

}  // namespace fovea
