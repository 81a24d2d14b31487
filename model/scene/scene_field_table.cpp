// The scene field table: every field of the scene file, one line each, in file order
// (docs/scene-format.md follows it). Adding a field = one line here (plus the member).
#include <string>

#include "model/scene/scene_fields.h"
#include "model/scene/scene_io.h"

namespace fovea {

bool isRotationAxis(const std::string& axis) {
  return axis == "yaw" || axis == "pitch" || axis == "roll";
}

namespace {

constexpr Presence kReq = Presence::Required, kOpt = Presence::Optional;
const Range kCoord = Range::closed(-1e5, 1e5);         // mm
const Range kAngle = Range::closed(-360.0, 360.0);     // deg
const Range kWavelength = Range::open(200.0, 2000.0);  // nm
const Range kIndex = Range::closed(1.0, 4.0);
const Range kPixels = Range::closed(1, 100000);
const Range kPositive = Range::positive(), kNonNegative = Range::nonNegative();

template <auto PoseMember, class T>
void addPose(FieldTable<T>& t, const std::string& centre) {
  t.group("Pose");
  t.template add<PoseMember, &Pose::position_mm>("position_mm", "mm", kCoord, kReq,
                                                 {"Position x", "Position y", "Position z"}, centre);
  t.template add<PoseMember, &Pose::rotation_deg>("rotation_deg", "deg", kAngle, kOpt, {"Yaw", "Pitch", "Roll"},
                                                  "yaw (about +y), pitch (about the turned +x), roll (about the "
                                                  "turned +z): R = Ry(yaw) Rx(-pitch) Rz(roll)");
}

std::string problemIf(bool bad, const std::string& what) {
  return bad ? what : std::string();
}

FieldTable<Projector> makeProjector() {
  using P = Projector;
  using B = PixelBeamModel;
  FieldTable<P> t;
  t.group("Identity").text<&P::name>("name", kOpt, "Name", "label of the projector");
  addPose<&P::pose>(t, "exit pupil in the bench frame; local +z = emission axis");
  t.group("Image");
  t.add<&P::pixels>("pixels", "px", kPixels, kReq, {"Pixels horizontal", "Pixels vertical"}, "pixel count");
  t.add<&P::fov_deg>("fov_deg", "deg", Range::open(0, 180), kReq, {"FOV horizontal", "FOV vertical"},
                     "full horizontal, vertical projection angles");
  t.add<&P::wavelengths_nm>("wavelengths_nm", "nm", kWavelength, kReq, {"Wavelengths"}, "laser wavelengths");
  t.add<&P::exit_pupil_diameter_mm>("exit_pupil_diameter_mm", "mm", kPositive, kOpt, {"Exit pupil diameter"},
                                    "scanner exit pupil");
  t.group("Pixel beam").object("pixel_beam", kOpt);
  t.add<&P::pixel_beam, &B::waist_distance_mm>("pixel_beam.waist_distance_mm", "mm", kPositive, kReq,
                                               {"Waist distance"}, "throw at which the pixel is smallest (A.2.1)");
  t.add<&P::pixel_beam, &B::waist_fwhm_um>("pixel_beam.waist_fwhm_um", "µm", kPositive, kReq, {"Waist FWHM"},
                                           "pixel FWHM at the waist");
  t.add<&P::pixel_beam, &B::divergence_mrad>("pixel_beam.divergence_mrad", "mrad", kNonNegative, kReq,
                                             {"Divergence (full, FWHM)"},
                                             "full-angle FWHM growth rate after the waist");
  t.add<&P::pixel_beam, &B::exit_fwhm_um>("pixel_beam.exit_fwhm_um", "µm", kPositive, kReq, {"Exit FWHM (long axis)"},
                                          "pixel FWHM at the exit pupil (long axis)");
  t.add<&P::pixel_beam, &B::exit_ellipticity>("pixel_beam.exit_ellipticity", "", Range::closed(1, 100), kReq,
                                              {"Exit ellipticity"}, "long/short axis ratio at the exit");
  return t;
}

FieldTable<Hoe> makeHoe() {
  FieldTable<Hoe> t;
  t.group("Identity").text<&Hoe::name>("name", kOpt, "Name", "label of the HOE carrier");
  addPose<&Hoe::pose>(t, "centre of the layer stack; local +z = film normal");
  t.group("Plate");
  t.add<&Hoe::size_mm>("size_mm", "mm", Range::open(0, 1e4), kReq, {"Width", "Height"},
                       "width (local x), height (local y)");
  t.add<&Hoe::substrate_thickness_mm>("substrate_thickness_mm", "mm", Range::closed(0, 100), kOpt,
                                      {"Substrate thickness"}, "glass on the world side (0 = film only)");
  t.add<&Hoe::cover_index>("cover_index", "", kIndex, kOpt, {"Cover index (eye side)"},
                           "medium on the eye side of the stack");
  t.add<&Hoe::substrate_index>("substrate_index", "", kIndex, kOpt, {"Substrate index (world side)"},
                               "medium on the world side of the stack");
  return t;
}

FieldTable<HoeLayer> makeHoeLayer() {
  using L = HoeLayer;
  using R = HoeRecording;
  FieldTable<L> t;
  t.group("Film").text<&L::name>("name", kOpt, "Name", "e.g. \"green\"");
  t.add<&L::thickness_um>("thickness_um", "µm", Range::openClosed(0, 10000), kReq, {"Thickness"}, "film thickness");
  t.add<&L::offset_um>("offset_um", "µm", Range::closed(-1e5, 1e5), kOpt, {"Offset along normal"},
                       "layer centre along the HOE's local +z from the stack centre");
  t.add<&L::n0>("n0", "", kIndex, kReq, {"Mean index n0"}, "mean index of the processed film");
  t.add<&L::n1>("n1", "", kNonNegative, kReq, {"Index modulation n1"}, "index modulation amplitude");
  t.rule("n1", "< n0", [](const L& l) {
    return problemIf(l.n1 >= l.n0, "must be < n0 (" + formatNumber(l.n0) + "), got " + formatNumber(l.n1));
  });
  t.add<&L::absorption_per_mm>("absorption_per_mm", "1/mm", kNonNegative, kOpt, {"Absorption"},
                               "intensity absorption coefficient alpha");
  t.add<&L::shrinkage_percent>("shrinkage_percent", "%", Range::open(-50, 50), kOpt, {"Shrinkage"},
                               "thickness change along the normal by processing (negative = thinner)");
  t.add<&L::recording_n0_delta>("recording_n0_delta", "", Range::closed(-0.5, 0.5), kOpt, {"n0 change since recording"},
                                "n0(recording) = n0 - recording_n0_delta");
  t.group("Recording").object("recording", kReq);
  t.add<&L::recording, &R::wavelength_nm>("recording.wavelength_nm", "nm", kWavelength, kReq, {"Recording wavelength"},
                                          "recording wavelength (B.1)");
  t.add<&L::recording, &R::reference_point_mm>("recording.reference_point_mm", "mm", kCoord, kReq,
                                               {"Reference x", "Reference y", "Reference z"},
                                               "diverging reference source (the projector), HOE at its nominal pose");
  t.add<&L::recording, &R::signal_point_mm>("recording.signal_point_mm", "mm", kCoord, kReq,
                                            {"Signal focus x", "Signal focus y", "Signal focus z"},
                                            "converging signal focus (the pupil centre), HOE at its nominal pose");
  t.add<&L::recording, &R::phase_conjugate>("recording.phase_conjugate", "", Range::any(), kOpt,
                                            {"Phase-conjugate recording"},
                                            "recorded with the time-reversed pair (B.1.2)");
  t.rule("recording.signal_point_mm", "", [](const L& l) {
    return problemIf(l.recording.reference_point_mm == l.recording.signal_point_mm,
                     "must differ from reference_point_mm (no fringes otherwise)");
  });
  return t;
}

FieldTable<Eye> makeEye() {
  FieldTable<Eye> t;
  t.group("Anatomy");
  t.add<&Eye::eyeball_diameter_mm>("eyeball_diameter_mm", "mm", Range::open(5, 50), kReq, {"Eyeball diameter"},
                                   "23 mm in the seed");
  t.add<&Eye::pupil_diameter_mm>("pupil_diameter_mm", "mm", Range::open(0, 15), kReq, {"Pupil diameter"},
                                 "5 mm in the seed");
  t.rule("pupil_diameter_mm", "", [](const Eye& e) {
    return problemIf(e.pupil_diameter_mm >= e.eyeball_diameter_mm, "must be smaller than eyeball_diameter_mm");
  });
  t.group("Placement");
  t.add<&Eye::relief_mm>("relief_mm", "mm", kPositive, kReq, {"Eye relief"},
                         "pupil centre (zero gaze) to HOE centre along the bench z axis");
  t.add<&Eye::lateral_offset_mm>("lateral_offset_mm", "mm", kCoord, kOpt, {"Lateral offset x", "Lateral offset y"},
                                 "decentration (x, y) of the eye");
  t.group("Gaze");
  t.add<&Eye::gaze_deg>("gaze_deg", "deg", Range::open(-90, 90), kOpt, {"Gaze yaw", "Gaze pitch"},
                        "yaw (+ towards +x), pitch (+ up)");
  t.add<&Eye::gaze_range_deg>("gaze_range_deg", "deg", Range::open(-90, 90), kOpt, {"Gaze range from", "Gaze range to"},
                              "design range of gaze angles");
  t.rule("gaze_range_deg", "", [](const Eye& e) {
    return problemIf(e.gaze_range_deg[0] >= e.gaze_range_deg[1], "lower end must be below the upper end");
  });
  t.group("Anatomy");
  t.add<&Eye::fovea_radius_deg>("fovea_radius_deg", "deg", Range::open(0, 45), kOpt, {"Foveal radius"},
                                "foveal region served by the micro-OLED");
  return t;
}

FieldTable<FovealDisplay> makeFovealDisplay() {
  using F = FovealDisplay;
  using C = ImageCombiner;
  FieldTable<F> t;
  t.group("Identity").text<&F::name>("name", kOpt, "Name", "label of the micro-OLED");
  addPose<&F::pose>(t, "panel centre; local +z = emission direction");
  t.group("Panel");
  t.add<&F::size_mm>("size_mm", "mm", Range::open(0, 1e4), kReq, {"Active width", "Active height"}, "active area");
  t.add<&F::pixels>("pixels", "px", kPixels, kReq, {"Pixels horizontal", "Pixels vertical"}, "pixel count");
  t.add<&F::primaries_nm>("primaries_nm", "nm", kWavelength, kOpt, {"Primaries"}, "emission peaks");
  t.group("Image combiner").object("combiner", kReq);
  t.text<&F::combiner, &C::name>("combiner.name", kOpt, "Combiner name", "label of the image combiner");
  t.add<&F::combiner, &C::magnification>("combiner.magnification", "x", kPositive, kReq, {"Magnification"},
                                         "lateral magnification display -> virtual image (A.5.1)");
  t.add<&F::combiner, &C::eye_distance_mm>("combiner.eye_distance_mm", "mm", kPositive, kReq, {"Distance to pupil"},
                                           "combiner (eye-side principal plane) to pupil");
  t.add<&F::combiner, &C::image_distance_mm>("combiner.image_distance_mm", "mm", kPositive, kReq,
                                             {"Virtual image distance"}, "virtual image distance from the eye");
  t.add<&F::combiner, &C::mtf30_cpd_on_axis>("combiner.mtf30_cpd_on_axis", "cyc/deg", kPositive, kOpt,
                                             {"MTF30 on axis"}, "optical limit on axis (Fig. S7)");
  t.add<&F::combiner, &C::field_curvature_per_deg2>("combiner.field_curvature_per_deg2", "1/deg²", kNonNegative, kOpt,
                                                    {"Field curvature"}, "fractional MTF30 drop per deg² off axis");
  return t;
}

FieldTable<BeamShapingLens> makeLens() {
  using L = BeamShapingLens;
  FieldTable<L> t;
  t.group("Identity");
  t.add<&L::enabled>("enabled", "", Range::any(), kReq, {"In the beam path"}, "whether the lens is in the beam");
  t.text<&L::name>("name", kOpt, "Name", "label of the lens");
  addPose<&L::pose>(t, "lens centre; local +z = lens axis");
  t.group("Optics");
  t.add<&L::focal_length_mm>("focal_length_mm", "mm", Range::closed(-1e5, 1e5), kReq, {"Focal length"},
                             "focal length (negative: diverging)");
  t.rule("focal_length_mm", "!= 0", [](const L& l) { return problemIf(l.focal_length_mm == 0.0, "must not be 0"); });
  t.add<&L::diameter_mm>("diameter_mm", "mm", kPositive, kReq, {"Diameter"}, "clear aperture");
  t.add<&L::center_thickness_mm>("center_thickness_mm", "mm", kNonNegative, kOpt, {"Centre thickness"},
                                 "centre thickness");
  t.add<&L::index>("index", "", kIndex, kOpt, {"Refractive index"}, "refractive index (N-BK7 at ~550 nm)");
  return t;
}

FieldTable<Foveation> makeFoveation() {
  using F = Foveation;
  FieldTable<F> t;
  t.group("Blend (blur start <= blend start < blend end)");
  t.add<&F::blur_start_deg>("blur_start_deg", "deg", Range::closed(0, 90), kReq, {"Blur starts"},
                            "eps_s: blur of the periphery image starts (B.2.3)");
  t.add<&F::blend_start_deg>("blend_start_deg", "deg", Range::closed(0, 90), kReq, {"Blend starts"},
                             "eps_o: intensity crossfade starts");
  t.add<&F::blend_end_deg>("blend_end_deg", "deg", Range::closed(0, 90), kReq, {"Blend ends"}, "eps_e: crossfade ends");
  t.rule("", "", [](const F& f) {
    return problemIf(!(f.blur_start_deg <= f.blend_start_deg && f.blend_start_deg < f.blend_end_deg),
                     "must satisfy blur_start_deg <= blend_start_deg < blend_end_deg");
  });
  return t;
}

FieldTable<StageBinding> makeStage() {
  using S = StageBinding;
  FieldTable<S> t;
  t.axis_unit = [](const S& s) -> std::string { return isRotationAxis(s.axis) ? "deg" : "mm"; };
  t.group("Binding");
  t.text<&S::element>("element", kReq, "Element", "driven element",
                      {"hoe", "foveal_display", "projector", "beam_shaping_lens", "camera"});
  t.text<&S::axis>("axis", kReq, "Axis", "element coordinate (yaw, pitch, roll in deg; x, y, z in mm)",
                   {"x", "y", "z", "yaw", "pitch", "roll"});
  t.group("Hardware");
  t.text<&S::controller>("controller", kReq, "Controller", "Thorlabs controller",
                         {"KDC101", "TDC001", "KBD101", "K10CR1"});
  t.text<&S::stage_model>("stage_model", kReq, "Stage", "stage model", {"MTS25-Z8", "Z825B", "DDSM50", "K10CR1"});
  t.text<&S::serial>("serial", kOpt, "Serial number", "controller serial number (empty: any / virtual)");
  t.add<&S::channel>("channel", "", Range::closed(1, 4), kOpt, {"Channel"}, "controller channel");
  t.group("Travel");
  t.add<&S::soft_limits>("soft_limits", "", kCoord, kReq, {"Soft limit low", "Soft limit high"},
                         "allowed travel in the element coordinate")
      .axisUnit();
  t.rule("soft_limits", "", [](const S& s) {
    return problemIf(s.soft_limits[0] >= s.soft_limits[1], "lower limit must be below the upper limit");
  });
  t.add<&S::home_offset>("home_offset", "", kCoord, kOpt, {"Home offset"}, "element coordinate when the stage reads 0")
      .axisUnit();
  t.add<&S::counts_per_unit>("counts_per", "", Range::open(0, 1e9), kOpt, {"Encoder counts per unit"},
                             "calibrated counts per mm (deg); absent: the stage model's figure")
      .axisUnit()
      .omitDefault();
  t.group("Controller set-up (written on connect)").object("controller_setup", kOpt);
  t.add<&S::setup, &StageControllerSetup::max_velocity>("controller_setup.max_velocity", "", Range::open(0, 1e4), kOpt,
                                                        {"Max velocity"}, "mm/s (deg/s); absent: the controller's")
      .omitDefault();
  t.add<&S::setup, &StageControllerSetup::acceleration>("controller_setup.acceleration", "", Range::open(0, 1e5), kOpt,
                                                        {"Acceleration"}, "mm/s^2 (deg/s^2)")
      .omitDefault();
  t.add<&S::setup, &StageControllerSetup::jog_step>("controller_setup.jog_step", "", Range::open(0, 1e3), kOpt,
                                                    {"Jog step"}, "mm (deg), single-step jogs")
      .omitDefault();
  t.add<&S::setup, &StageControllerSetup::home_velocity>("controller_setup.home_velocity", "", Range::open(0, 1e4),
                                                         kOpt, {"Home velocity"}, "mm/s (deg/s)")
      .omitDefault();
  t.text<&S::setup, &StageControllerSetup::limit_switches>("controller_setup.limit_switches", kOpt, "Limit switches",
                                                           "hard limit switches: ignore, makes or breaks on contact",
                                                           {"ignore", "makes", "breaks"})
      .omitDefault();
  return t;
}

FieldTable<ViewState> makeView() {
  using V = ViewState;
  FieldTable<V> t;
  t.group("Trace");
  t.add<&V::hoe_follows_gaze>("hoe_follows_gaze", "", Range::any(), kOpt, {"HOE follows gaze"},
                              "the HOE travels by x_p(alpha), the shift that maximises the FOV (A.4)")
      .omitDefault();
  t.text<&V::xp_rule>("xp_rule", kOpt, "x_p rule",
                      "how x_p is chosen: plateau-middle, the middle of the FOV plateau (ours); follow-focus, the "
                      "diffracted rays' focus on the rotated pupil centre (the seed's)",
                      {"plateau-middle", "follow-focus"})
      .omitDefault();
  return t;
}

// The binocular block (issue 30). IPD range: Dodgson 2004 ("Variation and extrema of human
// interpupillary distance", Proc. SPIE 5291) gives an adult mean of 63 mm, almost all adults
// within 45-80 mm and children from 5 years upwards above 40 mm; [40, 90] admits all of them.
FieldTable<Binocular> makeBinocular() {
  using B = Binocular;
  FieldTable<B> t;
  t.group("Binocular");
  t.text<&B::mode>("mode", kOpt, "Binocular mode",
                   "mirror: the left eye's train is the mirror image of the scene's (right) train about the "
                   "mid-plane, ipd_mm / 2 nasal of the right eye's rotation centre; explicit: the block's \"left\" "
                   "holds the left eye's train",
                   {"mirror", "explicit"});
  t.add<&B::ipd_mm>("ipd_mm", "mm", Range::closed(40, 90), kOpt, {"Interpupillary distance"},
                    "distance between the eyes' rotation centres (63 mm: the adult mean)");
  t.add<&B::fixation_distance_mm>("fixation_distance_mm", "mm", Range::closed(0, 1e5), kOpt, {"Fixation distance"},
                                  "0: off (the left eye's gaze mirrors the right one's); else the distance from "
                                  "midway between the eyes of the point both fixate on the right eye's line of sight "
                                  "(the Gaze dock sets 300-2500 mm)")
      .omitDefault();
  return t;
}

}  // namespace

// Each table is built once, on first use.
template <class T, FieldTable<T> (*Make)()>
const FieldTable<T>& built() {
  static const FieldTable<T> table = Make();
  return table;
}

const FieldTable<Projector>& projectorFields() {
  return built<Projector, makeProjector>();
}
const FieldTable<Hoe>& hoeFields() {
  return built<Hoe, makeHoe>();
}
const FieldTable<HoeLayer>& hoeLayerFields() {
  return built<HoeLayer, makeHoeLayer>();
}
const FieldTable<Eye>& eyeFields() {
  return built<Eye, makeEye>();
}
const FieldTable<FovealDisplay>& fovealDisplayFields() {
  return built<FovealDisplay, makeFovealDisplay>();
}
const FieldTable<BeamShapingLens>& lensFields() {
  return built<BeamShapingLens, makeLens>();
}
const FieldTable<Foveation>& foveationFields() {
  return built<Foveation, makeFoveation>();
}
const FieldTable<StageBinding>& stageFields() {
  return built<StageBinding, makeStage>();
}
const FieldTable<ViewState>& viewFields() {
  return built<ViewState, makeView>();
}
const FieldTable<Binocular>& binocularFields() {
  return built<Binocular, makeBinocular>();
}

}  // namespace fovea
