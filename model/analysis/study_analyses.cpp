#include "model/analysis/study_analyses.h"

#include <stdexcept>

#include "model/analysis/accommodation_resolution.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/angular_resolution.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/lens_catalog.h"
#include "model/analysis/trace_evaluator.h"
#include "model/analysis/trace_fov.h"

namespace fovea::analysis {

namespace {
const std::vector<std::string> kPolarizations{"unpolarized", "s", "p"};

Polarization polarizationFrom(const nlohmann::json& v) {
  return *parsePolarization(textOf(v, "polarization"));  // a validated choice
}

std::vector<ParameterSpec> gazeRangeParameters(double from, double to, const std::string& step_help) {
  return {
      gazeAngle("gaze-from", "Gaze from", from, "first gaze angle"),
      gazeAngle("gaze-to", "Gaze to", to, "last gaze angle"),
      positive("gaze-step", "Gaze step", "deg", 5.0, 90.0, 2, step_help),
      choice("axis", "Axis", {"yaw", "pitch"}, "yaw", "yaw: horizontal, HOE local x; pitch: vertical, HOE local y")};
}

ParameterSpec sourceShiftParameter() {
  return choice("source-shift", "Source shift", {"bench-z", "axial"}, "bench-z",
                "how the point source moves: bench-z, along bench z (ours); axial, along the projector's own optical "
                "axis, + towards the HOE (the seed's z_s, A.4)");
}

ShiftMethod sourceMethodFrom(const nlohmann::json& v) {
  return textOf(v, "source-shift") == "axial" ? ShiftMethod::SourceAxial : ShiftMethod::Source;
}

// The seed's FOV definition is only computed by the exact estimator.
std::optional<ParameterProblem> checkFovDefinition(const nlohmann::json& v) {
  if (textOf(v, "fov-definition") == "seed" && textOf(v, "fov-method") != "edges")
    return ParameterProblem{"fov-definition", "'seed' needs --fov-method edges (footprint angles of single rays)"};
  return std::nullopt;
}

std::optional<ParameterProblem> checkGazeStudy(const nlohmann::json& v) {
  if (auto p = checkGazeRange(v)) return p;
  return checkFovDefinition(v);
}

// The definitions a gaze study's document states it used.
void addDefinitions(nlohmann::json& out, const nlohmann::json& v) {
  out["fov_method"] = textOf(v, "fov-method");
  out["fov_definition"] = textOf(v, "fov-definition");
  out["eyebox_criterion"] = textOf(v, "eyebox-criterion");
  out["xp_rule"] = textOf(v, "xp-rule");
}

OptionGroup gazeGroup(bool repeatable) {
  return {"gaze-deg", {"gaze-yaw", "gaze-pitch"}, "YAW[,PITCH] gaze in degrees", repeatable};
}
}  // namespace

std::vector<ParameterSpec> studyParameters() {
  // 3 deg: above the 1-2 deg jitter of the ray-sampled FOV (gaze_studies.h), so that the eye
  // box measures the optics, not the ray sampling; 12 000 rays per wavelength per trace.
  return {integer("rays", "Rays per wavelength", 12000, 50, 1000000, "rays per wavelength per trace"),
          number("tolerance-deg", "Eye-box tolerance", "deg", 3.0, 0.0, 90.0, 2,
                 "eye-box criterion tolerance: FOV within this of the zero-gaze FOV"),
          choice("fov-method", "FOV estimator", {"edges", "dense"}, "edges",
                 "edges: the field's edges root-found to 0.005 deg (fov_edges.h); dense: counted on the rays grid"),
          choice("eyebox-criterion", "Eye-box criterion", {"tolerance", "centre-fov"}, "tolerance",
                 "tolerance: FOV within tolerance-deg of the zero-gaze FOV (ours); centre-fov: FOV at least the "
                 "zero-gaze FOV (the seed's A.3)"),
          choice("fov-definition", "FOV definition", {"ours", "seed"}, "ours",
                 "ours: span of the lit rays' arrival directions; seed: span of their plate points seen from the "
                 "pupil centre, the lit footprint (C.2, Fig. S5; needs fov-method edges)"),
          choice("xp-rule", "x_p rule", {"plateau-middle", "follow-focus"}, "plateau-middle",
                 "how the HOE shift x_p is chosen: plateau-middle, the middle of the FOV plateau (ours); follow-focus, "
                 "the diffracted rays' least-squares focus on the rotated pupil centre (the seed's; gaze_studies.h)")};
}

std::optional<std::array<double, 2>> gazeFrom(const nlohmann::json& v) {
  const auto yaw = optionalNumberOf(v, "gaze-yaw"), pitch = optionalNumberOf(v, "gaze-pitch");
  if (!yaw && !pitch) return std::nullopt;
  return std::array<double, 2>{yaw.value_or(0.0), pitch.value_or(0.0)};
}

TraceOptions traceOptionsFrom(const nlohmann::json& v) {
  TraceOptions o;
  o.gaze_deg = gazeFrom(v);
  o.hoe_shift_mm = {numberOf(v, "hoe-shift-x"), numberOf(v, "hoe-shift-y")};
  o.source_shift_mm = numberOf(v, "source-shift-mm");
  o.wavelength_nm = optionalNumberOf(v, "wavelength-nm");
  o.rays = integerOf(v, "rays");
  o.efficiency_threshold = numberOf(v, "threshold");
  o.polarization = polarizationFrom(v);
  o.keep_field_rays = true;  // the dense continuous FOV (fov_dense_deg)
  return o;
}

FovMethod traceFovMethodFrom(const nlohmann::json& v) {
  return parseFovMethod(textOf(v, "fov-method")).value_or(FovMethod::Edges);
}

FovEvaluator evaluatorFrom(const nlohmann::json& v) {
  TraceEvaluatorOptions t;
  t.rays = integerOf(v, "rays");
  t.fov_method = parseFovMethod(textOf(v, "fov-method")).value_or(FovMethod::Edges);
  t.fov_angle = parseFovDefinition(textOf(v, "fov-definition")).value_or(FovAngle::Arrival);
  return traceEvaluator(t);
}

GazeStudyOptions gazeStudyOptionsFrom(const nlohmann::json& v) {
  GazeStudyOptions g;
  g.tolerance_deg = numberOf(v, "tolerance-deg");
  g.criterion = textOf(v, "eyebox-criterion") == "centre-fov" ? EyeBoxCriterion::CentreFov : EyeBoxCriterion::Tolerance;
  g.xp_rule = parseXpRule(textOf(v, "xp-rule")).value_or(XpRule::PlateauMiddle);
  return g;
}

GazeAxis axisFrom(const nlohmann::json& v) {
  return textOf(v, "axis") == "pitch" ? GazeAxis::Pitch : GazeAxis::Yaw;
}

SelectivityOptions selectivityOptionsFrom(const nlohmann::json& v) {
  SelectivityOptions o;
  o.point_mm = {numberOf(v, "point-u"), numberOf(v, "point-v")};
  o.angle_span_deg = numberOf(v, "angle-span-deg");
  o.wavelength_span_nm = numberOf(v, "wavelength-span-nm");
  o.angle_samples = o.wavelength_samples = integerOf(v, "samples");
  o.polarization = polarizationFrom(v);
  return o;
}

AnalysisDefinition traceAnalysis() {
  AnalysisDefinition d;
  d.id = "trace";
  d.title = "Trace (retinal FOV at one gaze)";
  d.description =
      "Projector -> recorded HOE stack -> eye: retinal FOV, rays in the pupil and mean efficiency, per wavelength.";
  ParameterSpec yaw = gazeAngle("gaze-yaw", "Gaze yaw", nullptr, "gaze yaw (+ towards the projector's side)");
  ParameterSpec pitch = gazeAngle("gaze-pitch", "Gaze pitch", nullptr, "gaze pitch (+ up)");
  yaw.unset_meaning = pitch.unset_meaning = "the scene's gaze";
  ParameterSpec wavelength =
      positive("wavelength-nm", "Wavelength", "nm", nullptr, 2000.0, 1, "trace only this wavelength");
  wavelength.unset_meaning = "every projector laser";
  d.parameters = {
      yaw,
      pitch,
      number("hoe-shift-x", "HOE shift x", "mm", 0.0, -50, 50, 3, "lateral HOE shift, local x"),
      number("hoe-shift-y", "HOE shift y", "mm", 0.0, -50, 50, 3, "lateral HOE shift, local y"),
      number("source-shift-mm", "Source shift", "mm", 0.0, -100, 100, 3, "projector point-source shift along bench z"),
      wavelength,
      integer("rays", "Rays per wavelength", 4000, 1, 10000000,
              "approximate rays per wavelength over the projector FOV"),
      number("threshold", "Efficiency threshold", "", 0.1, 0, 1, 3, "rays below it do not count for the FOV"),
      choice("polarization", "Polarisation", kPolarizations, "unpolarized", "projector light"),
      choice("fov-method", "FOV estimator", {"edges", "dense"}, "edges",
             "fov_deg from edges: the exact estimator, the field's edges root-found to 0.005 deg (fov_edges.h, as "
             "sweep); dense: counted on the traced ray grid (also always in fov_dense_deg)")};
  d.option_groups = {
      gazeGroup(true),
      {"hoe-shift-mm", {"hoe-shift-x", "hoe-shift-y"}, "X[,Y] lateral HOE shift in its local frame (mm)"}};
  d.run = [](const Scene& scene, const nlohmann::json& v, const StudyControl&) -> std::optional<nlohmann::json> {
    const TraceOptions o = traceOptionsFrom(v);
    const TraceResult r = traceScene(scene, o);
    return traceResultJson(r, o, traceFov(scene, r, o), traceFovMethodFrom(v));
  };
  return d;
}

ShiftMethod sweepMethodFrom(const nlohmann::json& v) {
  return textOf(v, "method") == "source" ? sourceMethodFrom(v) : ShiftMethod::Hoe;
}

nlohmann::json sweepDocument(const GazeSweepResult& r, const nlohmann::json& v) {
  nlohmann::json out = sweepResultJson(r, textOf(v, "axis"));
  addDefinitions(out, v);
  out["source_shift"] = textOf(v, "source-shift");
  return out;
}

AnalysisDefinition sweepAnalysis() {
  AnalysisDefinition d;
  d.id = "sweep";
  d.title = "Sweep: HOE travel and FOV vs gaze";
  d.description = "For each gaze, the lateral HOE shift that maximises the FOV (supplement A.3), and the eye box.";
  d.parameters = gazeRangeParameters(-20, 20, "gaze step (> 0)");
  d.parameters.push_back(choice("method", "Method", {"hoe", "source"}, "hoe",
                                "hoe: move the HOE laterally; source: move the projector point source (source-shift)"));
  d.parameters.push_back(sourceShiftParameter());
  for (auto& p : studyParameters()) d.parameters.push_back(p);
  d.plots = {"fov-vs-gaze", "travel-vs-gaze"};
  d.cached = true;
  d.check = checkGazeStudy;
  d.run = [](const Scene& scene, const nlohmann::json& v,
             const StudyControl& control) -> std::optional<nlohmann::json> {
    const auto r =
        sweepGaze(scene, evaluatorFrom(v), numberOf(v, "gaze-from"), numberOf(v, "gaze-to"), numberOf(v, "gaze-step"),
                  axisFrom(v), sweepMethodFrom(v), gazeStudyOptionsFrom(v), control);
    if (!r.ok()) return std::nullopt;
    return sweepDocument(*r.value, v);
  };
  return d;
}

std::optional<nlohmann::json> compareShiftStudy(const Scene& scene, const nlohmann::json& v,
                                                const StudyControl& control) {
  const FovEvaluator eval = evaluatorFrom(v);
  EyeBox boxes[3];  // hoe, source, static
  std::vector<GazeSample> source_samples;
  int done = 0;
  for (ShiftMethod m : {ShiftMethod::Hoe, sourceMethodFrom(v), ShiftMethod::None}) {
    StudyControl third;
    third.cancel = control.cancel;
    if (control.on_progress) third.on_progress = [&control, done](double f) { control.on_progress((done + f) / 3.0); };
    const auto r = sweepGaze(scene, eval, numberOf(v, "gaze-from"), numberOf(v, "gaze-to"), numberOf(v, "gaze-step"),
                             axisFrom(v), m, gazeStudyOptionsFrom(v), third);
    if (!r.ok()) return std::nullopt;
    if (done == 1) source_samples = r.value->samples;
    boxes[done++] = r.value->eyebox;
  }
  nlohmann::json out = compareShiftJson(boxes[0], boxes[1], &boxes[2], axisFrom(v), sourceMethodFrom(v));
  out["source_shift"]["samples"] = sourceShiftSamplesJson(source_samples, axisFrom(v));
  addDefinitions(out, v);
  return out;
}

AnalysisDefinition compareShiftAnalysis() {
  AnalysisDefinition d;
  d.id = "compare-shift";
  d.title = "Compare shift: HOE vs point source";
  d.description = "Dynamic eye box: moving the HOE vs moving the projector point source (supplement A.4).";
  d.parameters = gazeRangeParameters(-40, 40, "coarse step before the borders are bisected");
  d.parameters.push_back(sourceShiftParameter());
  for (auto& p : studyParameters()) d.parameters.push_back(p);
  d.cached = true;
  d.check = checkGazeStudy;
  d.run = compareShiftStudy;
  return d;
}

AnalysisDefinition sensitivityAnalysis() {
  AnalysisDefinition d;
  d.id = "sensitivity";
  d.title = "Sensitivity to one scene parameter";
  d.description =
      "FOV, mean efficiency and efficiency uniformity at the scene's gaze over values of any numeric scene "
      "parameter (its JSON path in the scene file); when the scene's HOE follows the gaze (view.hoe_follows_gaze) "
      "each value is traced with its own x_p (xp-rule).";
  d.parameters = {text("parameter", "Parameter (JSON path)",
                       {"eye.relief_mm", "eye.pupil_diameter_mm", "hoe_layers[1].shrinkage_percent", "hoe_layers[1].n1",
                        "hoe_layers[1].thickness_um", "hoe.rotation_deg[0]", "projector.position_mm[2]"},
                       "eye.relief_mm", "JSON path of a number in the scene file, e.g. eye.relief_mm"),
                  number("from", "From", "", 18.0, -1e6, 1e6, 4, "first value"),
                  number("to", "To", "", 26.0, -1e6, 1e6, 4, "last value"),
                  integer("steps", "Steps", 5, 1, 10000, "number of values")};
  for (auto& p : studyParameters()) d.parameters.push_back(p);
  d.plots = {"sensitivity"};
  d.cached = true;
  d.check = checkFovDefinition;
  d.run = [](const Scene& scene, const nlohmann::json& v,
             const StudyControl& control) -> std::optional<nlohmann::json> {
    const std::string path = textOf(v, "parameter");
    double nominal = 0;
    try {  // both ends must give a valid scene before any work
      nominal = parameterValue(scene, path);
      withParameter(scene, path, numberOf(v, "from"));
      withParameter(scene, path, numberOf(v, "to"));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("parameter: ") + e.what());
    }
    std::optional<GazeStudyOptions> follow;
    if (scene.view.hoe_follows_gaze) follow = gazeStudyOptionsFrom(v);
    const auto r = sensitivitySweep(scene, evaluatorFrom(v), path, numberOf(v, "from"), numberOf(v, "to"),
                                    integerOf(v, "steps"), control, follow);
    if (!r.ok()) return std::nullopt;
    nlohmann::json out = sensitivityResultJson(*r.value, path, nominal);
    addDefinitions(out, v);
    out["hoe_follows_gaze"] = scene.view.hoe_follows_gaze;
    return out;
  };
  return d;
}

AnalysisDefinition resolutionAnalysis() {
  AnalysisDefinition d;
  d.id = "resolution";
  d.title = "Angular resolution vs eccentricity";
  d.description = "Foveal, peripheral, optical-limit and perceived resolution (cpd) for one gaze (supplement A.5).";
  ParameterSpec yaw = gazeAngle("gaze-yaw", "Gaze yaw", nullptr, "gaze yaw");
  ParameterSpec pitch = gazeAngle("gaze-pitch", "Gaze pitch", nullptr, "gaze pitch");
  yaw.unset_meaning = pitch.unset_meaning = "the scene's gaze";
  ParameterSpec accommodation =
      text("accommodation-d", "Accommodation (D)", {"0.4,0.5,0.67,0.8,1,1.25,1.5,2,2.5,3,3.3"}, "",
           "comma list of accommodations in diopters, each in [0, 4] (0.4..3.3 D: the seed's 250..30 cm, C.3): "
           "peripheral and foveal cpd (MTF50, MTF10) of the retinal PSFs at the line of sight for each");
  accommodation.default_value = nullptr;
  accommodation.unset_meaning = "no accommodation sweep (\"accommodation\": null)";
  d.parameters = {yaw, pitch,
                  integer("samples", "Samples", 241, 3, 100000, "eccentricity samples over the peripheral field"),
                  accommodation};
  d.option_groups = {gazeGroup(false)};
  d.plots = {"resolution-vs-eccentricity", "resolution-vs-accommodation"};
  d.check = [](const nlohmann::json& v) -> std::optional<ParameterProblem> {
    if (!v.contains("accommodation-d") || v["accommodation-d"].is_null()) return std::nullopt;
    const AccommodationList list = parseAccommodationList(textOf(v, "accommodation-d"));
    if (list.problem) return ParameterProblem{"accommodation-d", *list.problem};
    return std::nullopt;
  };
  d.run = [](const Scene& scene, const nlohmann::json& v, const StudyControl&) -> std::optional<nlohmann::json> {
    ResolutionOptions o;
    o.samples = integerOf(v, "samples");
    o.gaze_deg = gazeFrom(v);
    const ResolutionResult r = analyzeResolution(scene, o);
    if (r.samples.empty())
      throw std::runtime_error("no line of sight reaches the HOE or the foveal image for this gaze");
    nlohmann::json out = resolutionResultJson(r, scene);
    out["accommodation"] = nullptr;
    if (v.contains("accommodation-d") && !v["accommodation-d"].is_null()) {
      const AccommodationList list = parseAccommodationList(textOf(v, "accommodation-d"));
      out["accommodation"] = accommodationResolutionJson(
          resolutionVsAccommodation(scene, {r.gaze_yaw_deg, r.gaze_pitch_deg}, list.values_d));
    }
    return out;
  };
  return d;
}

AnalysisDefinition optimizeLensAnalysis() {
  AnalysisDefinition d;
  d.id = "optimize-lens";
  d.title = "Optimise the beam-shaping lens";
  d.description =
      "Stock lens, position and Scheimpflug tilt minimising the RMS pixel spot on the HOE (supplement A.2), NLopt "
      "BOBYQA from several starts per catalogue lens.";
  ParameterSpec max_distance = positive("max-distance-mm", "Max lens distance", "mm", nullptr, 10000.0, 1,
                                        "farthest lens position from the projector along its axis");
  max_distance.unset_meaning = "15 mm short of the HOE";
  d.parameters = {integer("starts", "Starts per lens", 5, 1, 50, "optimiser starts per catalogue lens"), max_distance};
  d.plots = {"lens-candidates"};
  d.cached = true;
  d.run = [](const Scene& scene, const nlohmann::json& v,
             const StudyControl& control) -> std::optional<nlohmann::json> {
    LensOptimizationOptions o;
    o.starts_per_lens = integerOf(v, "starts");
    o.max_distance_mm = optionalNumberOf(v, "max-distance-mm");
    const auto r = optimizeBeamShapingLens(scene, defaultLensCatalog(), o, control);
    if (!r.ok()) return std::nullopt;
    return lensOptimizationJson(*r.value);
  };
  return d;
}

AnalysisDefinition selectivityAnalysis() {
  AnalysisDefinition d;
  d.id = "selectivity";
  d.title = "HOE layer selectivity (efficiency vs detuning)";
  d.description =
      "Angular and spectral selectivity of every recorded layer at one plate point: efficiency of the layer alone "
      "as the projector's probe is tilted or its wavelength swept.";
  d.parameters = {number("point-u", "Plate point u", "mm", 0.0, -500, 500, 3, "HOE local x of the point"),
                  number("point-v", "Plate point v", "mm", 0.0, -500, 500, 3, "HOE local y of the point"),
                  number("angle-span-deg", "Angle span (±)", "deg", 10.0, 0.01, 80, 2, "detuning range -A..A"),
                  number("wavelength-span-nm", "Wavelength span (±)", "nm", 40.0, 0.1, 500, 1,
                         "wavelength range around each layer"),
                  integer("samples", "Samples", 401, 11, 100001, "samples per curve"),
                  choice("polarization", "Polarisation", kPolarizations, "unpolarized", "probe light")};
  d.option_groups = {{"point-mm", {"point-u", "point-v"}, "U[,V] plate point in the HOE's local frame (mm)"}};
  d.plots = {"efficiency-vs-angle", "efficiency-vs-wavelength"};
  d.run = [](const Scene& scene, const nlohmann::json& v, const StudyControl&) -> std::optional<nlohmann::json> {
    if (scene.hoe_layers.empty()) throw std::runtime_error("the scene has no HOE layer");
    return selectivityResultJson(analyzeSelectivity(scene, selectivityOptionsFrom(v)));
  };
  return d;
}

}  // namespace fovea::analysis
