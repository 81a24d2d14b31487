#include "widgets/analyses/analysis_catalog.h"

#include <cmath>
#include <stdexcept>

#include "model/analysis/analysis_json.h"
#include "model/analysis/angular_resolution.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/hoe_selectivity.h"
#include "model/analysis/lens_catalog.h"
#include "model/analysis/trace_evaluator.h"
#include "model/physics/grating_request.h"
#include "model/physics/trace.h"
#include "model/rigorous/kogelnik_vs_rcwa.h"
#include "model/rigorous/rcwa_grating.h"
#include "model/scene/scene_io.h"

namespace fovea::widgets {

namespace {

using Kind = AnalysisParameter::Kind;

AnalysisParameter num(const QString& key, const QString& label, const QString& unit, double def, double lo, double hi,
                      int decimals, const QString& help) {
  AnalysisParameter p;
  p.key = key;
  p.label = label;
  p.unit = unit;
  p.kind = Kind::Number;
  p.defaultValue = def;
  p.minimum = lo;
  p.maximum = hi;
  p.decimals = decimals;
  p.help = help;
  return p;
}

AnalysisParameter integer(const QString& key, const QString& label, int def, int lo, int hi, const QString& help) {
  AnalysisParameter p = num(key, label, {}, def, lo, hi, 0, help);
  p.kind = Kind::Integer;
  return p;
}

AnalysisParameter choice(const QString& key, const QString& label, const QStringList& choices, const QString& def,
                         const QString& help) {
  AnalysisParameter p;
  p.key = key;
  p.label = label;
  p.kind = Kind::Choice;
  p.choices = choices;
  p.defaultValue = def;
  p.help = help;
  return p;
}

AnalysisParameter text(const QString& key, const QString& label, const QStringList& suggestions, const QString& def,
                       const QString& help) {
  AnalysisParameter p = choice(key, label, suggestions, def, help);
  p.kind = Kind::Text;
  return p;
}

QList<AnalysisParameter> studyOptions() {
  return {integer("rays", "Rays per wavelength", 1500, 50, 1000000, "rays per wavelength per trace"),
          num("tolerance-deg", "Eye-box tolerance", "deg", 1.0, 0.0, 90.0, 2,
              "eye-box criterion: FOV within this of the zero-gaze FOV")};
}

QList<AnalysisSpec> buildCatalog() {
  QList<AnalysisSpec> c;
  const QStringList pol{"unpolarized", "s", "p"};
  {
    AnalysisSpec s{
        "trace",
        "Trace (retinal FOV at one gaze)",
        "Projector -> recorded HOE stack -> eye: retinal FOV, rays in the pupil and mean efficiency, per "
        "wavelength.",
        {num("gaze-yaw", "Gaze yaw", "deg", 0, -60, 60, 2, "gaze yaw (+ towards the projector's side)"),
         num("gaze-pitch", "Gaze pitch", "deg", 0, -60, 60, 2, "gaze pitch (+ up)"),
         num("hoe-shift-x", "HOE shift x", "mm", 0, -50, 50, 3, "lateral HOE shift, local x"),
         num("hoe-shift-y", "HOE shift y", "mm", 0, -50, 50, 3, "lateral HOE shift, local y"),
         num("source-shift-mm", "Source shift", "mm", 0, -100, 100, 3, "projector point-source shift along bench z"),
         num("wavelength-nm", "Wavelength (0 = all)", "nm", 0, 0, 2000, 1,
             "trace only this wavelength; 0 traces every projector laser"),
         integer("rays", "Rays per wavelength", 4000, 1, 10000000, "over the projector FOV"),
         num("threshold", "Efficiency threshold", {}, 0.1, 0, 1, 3, "rays below it do not count"),
         choice("polarization", "Polarisation", pol, "unpolarized", "projector light")},
        {},
        true};
    c << s;
  }
  {
    AnalysisSpec s{"sweep",
                   "Sweep: HOE travel and FOV vs gaze",
                   "For each gaze, the lateral HOE shift that maximises the FOV (supplement A.3), and the eye box.",
                   {num("gaze-from", "Gaze from", "deg", -20, -80, 80, 2, "first gaze angle"),
                    num("gaze-to", "Gaze to", "deg", 20, -80, 80, 2, "last gaze angle"),
                    num("gaze-step", "Gaze step", "deg", 5, 0.01, 90, 2, "gaze step (> 0)"),
                    choice("axis", "Axis", {"yaw", "pitch"}, "yaw", "yaw: HOE local x; pitch: HOE local y")},
                   {"fov-vs-gaze", "travel-vs-gaze"},
                   true};
    s.parameters << studyOptions();
    c << s;
  }
  {
    AnalysisSpec s{"compare-shift",
                   "Compare shift: HOE vs point source",
                   "Dynamic eye box: moving the HOE vs moving the projector point source (supplement A.4).",
                   {num("gaze-from", "Gaze from", "deg", -40, -80, 80, 2, "gaze range studied, first angle"),
                    num("gaze-to", "Gaze to", "deg", 40, -80, 80, 2, "last angle"),
                    num("gaze-step", "Gaze step", "deg", 5, 0.01, 90, 2, "coarse step before borders are bisected"),
                    choice("axis", "Axis", {"yaw", "pitch"}, "yaw", "gaze axis")},
                   {},
                   true};
    s.parameters << studyOptions();
    c << s;
  }
  {
    AnalysisSpec s{
        "sensitivity",
        "Sensitivity to one scene parameter",
        "FOV, mean efficiency and efficiency uniformity at the scene's gaze over values of any numeric "
        "scene parameter (its JSON path in the scene file).",
        {text("parameter", "Parameter (JSON path)",
              {"eye.relief_mm", "eye.pupil_diameter_mm", "hoe_layers[1].shrinkage_percent", "hoe_layers[1].n1",
               "hoe_layers[1].thickness_um", "hoe.rotation_deg[0]", "projector.position_mm[2]"},
              "eye.relief_mm", "JSON path of a number in the scene file"),
         num("from", "From", {}, 18, -1e6, 1e6, 4, "first value"), num("to", "To", {}, 26, -1e6, 1e6, 4, "last value"),
         integer("steps", "Steps", 5, 1, 10000, "number of values")},
        {"sensitivity"},
        true};
    s.parameters << studyOptions();
    c << s;
  }
  {
    AnalysisSpec s{"resolution",
                   "Angular resolution vs eccentricity",
                   "Foveal, peripheral, optical-limit and perceived resolution (cpd) for one gaze (supplement A.5).",
                   {num("gaze-yaw", "Gaze yaw", "deg", 0, -60, 60, 2, "gaze yaw"),
                    num("gaze-pitch", "Gaze pitch", "deg", 0, -60, 60, 2, "gaze pitch"),
                    integer("samples", "Samples", 241, 3, 100000, "eccentricity samples over the peripheral field")},
                   {"resolution-vs-eccentricity"},
                   true};
    c << s;
  }
  {
    AnalysisSpec s{"optimize-lens",
                   "Optimise the beam-shaping lens",
                   "Stock lens, position and Scheimpflug tilt minimising the RMS pixel spot on the HOE "
                   "(supplement A.2), NLopt BOBYQA from several starts per catalogue lens.",
                   {integer("starts", "Starts per lens", 5, 1, 50, "optimiser starts per catalogue lens")},
                   {"lens-candidates"},
                   true};
    c << s;
  }
  {
    AnalysisSpec s{"selectivity",
                   "HOE layer selectivity (efficiency vs detuning)",
                   "Angular and spectral selectivity of every recorded layer at one plate point: efficiency of the "
                   "layer alone as the projector's probe is tilted or its wavelength swept.",
                   {num("point-u", "Plate point u", "mm", 0, -500, 500, 3, "HOE local x of the point"),
                    num("point-v", "Plate point v", "mm", 0, -500, 500, 3, "HOE local y of the point"),
                    num("angle-span-deg", "Angle span (±)", "deg", 10, 0.01, 80, 2, "detuning range"),
                    num("wavelength-span-nm", "Wavelength span (±)", "nm", 40, 0.1, 500, 1, "around each layer"),
                    integer("samples", "Samples", 401, 11, 100001, "samples per curve"),
                    choice("polarization", "Polarisation", pol, "unpolarized", "probe light")},
                   {"efficiency-vs-angle", "efficiency-vs-wavelength"},
                   true};
    c << s;
  }
  {
    AnalysisSpec s{"grating",
                   "Planar grating: efficiency vs probe angle",
                   "One planar volume grating (the fovea-cli grating request) swept over the probe angle, with "
                   "Kogelnik's closed forms and optionally converged RCWA.",
                   {num("n0", "n0", {}, 1.5, 1.0, 4.0, 4, "mean refractive index"),
                    num("n1", "n1", {}, 0.02, 0.0, 1.0, 5, "index modulation amplitude"),
                    num("thickness-um", "Thickness", "um", 16, 0.0, 10000, 3, "film thickness"),
                    num("period-nm", "Period", "nm", 177.333, 1.0, 1e6, 3, "fringe period"),
                    num("slant-deg", "Slant", "deg", 0, -180, 180, 3, "angle of K from the film normal"),
                    num("probe-deg", "Probe (centre)", "deg", 0, -89.9, 89.9, 3, "probe angle inside the medium"),
                    num("wavelength-nm", "Wavelength", "nm", 532, 1, 100000, 2, "vacuum wavelength"),
                    choice("polarization", "Polarisation", pol, "s", "probe light"),
                    num("absorption-per-mm", "Absorption", "1/mm", 0, 0, 1e6, 4, "intensity absorption"),
                    num("span-deg", "Probe span (±)", "deg", 5, 0.01, 89, 3, "probe angles swept around the centre"),
                    integer("samples", "Samples", 201, 3, 20001, "probe angles"),
                    choice("model", "Model", {"kogelnik", "kogelnik+rcwa"}, "kogelnik",
                           "kogelnik+rcwa adds converged RCWA (slower)")},
                   {"efficiency-vs-angle"},
                   true};
    c << s;
  }
  {
    AnalysisSpec s{"kogelnik-vs-rcwa",
                   "Kogelnik vs RCWA: error and run time",
                   "Kogelnik's two-wave closed forms against converged RCWA over geometry, thickness, n1 and "
                   "detuning: error by the validity parameter rho and the time of each model (docs/benchmarks.md).",
                   {choice("grid", "Grid", {"quick", "full"}, "quick",
                           "quick: 24 points; full: the 240 points of "
                           "docs/benchmarks.md")},
                   {"time-vs-error"},
                   false};
    c << s;
  }
  return c;
}

double number(const AnalysisParams& p, const char* key) {
  return p.value(QString::fromLatin1(key)).toDouble();
}
int integerOf(const AnalysisParams& p, const char* key) {
  return p.value(QString::fromLatin1(key)).toInt();
}
std::string textOf(const AnalysisParams& p, const char* key) {
  return p.value(QString::fromLatin1(key)).toString().toStdString();
}

nlohmann::json paramsJson(const AnalysisParams& p) {
  nlohmann::json j = nlohmann::json::object();
  for (auto it = p.begin(); it != p.end(); ++it) {
    const QVariant& v = it.value();
    if (v.typeId() == QMetaType::Double || v.typeId() == QMetaType::Int || v.typeId() == QMetaType::LongLong)
      j[it.key().toStdString()] = v.toDouble();
    else
      j[it.key().toStdString()] = v.toString().toStdString();
  }
  return j;
}

Polarization polarizationOf(const AnalysisParams& p) {
  const auto pol = parsePolarization(textOf(p, "polarization"));
  if (!pol) throw std::invalid_argument("polarization: expected s, p or unpolarized");
  return *pol;
}

GazeAxis axisOf(const AnalysisParams& p) {
  return textOf(p, "axis") == "pitch" ? GazeAxis::Pitch : GazeAxis::Yaw;
}

FovEvaluator evaluatorOf(const AnalysisParams& p) {
  TraceEvaluatorOptions t;
  t.rays = integerOf(p, "rays");
  return traceEvaluator(t);
}

GazeStudyOptions gazeOptionsOf(const AnalysisParams& p) {
  GazeStudyOptions g;
  g.tolerance_deg = number(p, "tolerance-deg");
  return g;
}

void checkGazeRange(const AnalysisParams& p) {
  const double from = number(p, "gaze-from"), to = number(p, "gaze-to"), step = number(p, "gaze-step");
  if (!(step > 0)) throw std::invalid_argument("gaze-step: must be > 0");
  if (!(to >= from)) throw std::invalid_argument("gaze-to: must be >= gaze-from");
  if ((to - from) / step > 2000) throw std::invalid_argument("gaze-step: more than 2000 gaze samples");
}

std::optional<nlohmann::json> runTrace(const Scene& scene, const AnalysisParams& p) {
  TraceOptions o;
  o.gaze_deg = std::array<double, 2>{number(p, "gaze-yaw"), number(p, "gaze-pitch")};
  o.hoe_shift_mm = {number(p, "hoe-shift-x"), number(p, "hoe-shift-y")};
  o.source_shift_mm = number(p, "source-shift-mm");
  if (number(p, "wavelength-nm") > 0) o.wavelength_nm = number(p, "wavelength-nm");
  o.rays = integerOf(p, "rays");
  o.efficiency_threshold = number(p, "threshold");
  o.polarization = polarizationOf(p);
  return traceResultJson(traceScene(scene, o), o);
}

std::optional<nlohmann::json> runSweep(const Scene& scene, const AnalysisParams& p, const StudyControl& control) {
  checkGazeRange(p);
  const auto r = sweepGaze(scene, evaluatorOf(p), number(p, "gaze-from"), number(p, "gaze-to"), number(p, "gaze-step"),
                           axisOf(p), ShiftMethod::Hoe, gazeOptionsOf(p), control);
  if (!r.ok()) return std::nullopt;
  return sweepResultJson(*r.value, textOf(p, "axis"));
}

std::optional<nlohmann::json> runCompareShift(const Scene& scene, const AnalysisParams& p,
                                              const StudyControl& control) {
  checkGazeRange(p);
  const FovEvaluator eval = evaluatorOf(p);
  EyeBox boxes[2];
  int done = 0;
  for (ShiftMethod m : {ShiftMethod::Hoe, ShiftMethod::Source}) {
    StudyControl half;
    half.cancel = control.cancel;
    if (control.on_progress) half.on_progress = [&control, done](double f) { control.on_progress(0.5 * (done + f)); };
    const auto r = sweepGaze(scene, eval, number(p, "gaze-from"), number(p, "gaze-to"), number(p, "gaze-step"),
                             axisOf(p), m, gazeOptionsOf(p), half);
    if (!r.ok()) return std::nullopt;
    boxes[done++] = r.value->eyebox;
  }
  return compareShiftJson(boxes[0], boxes[1], nullptr, axisOf(p));
}

std::optional<nlohmann::json> runSensitivity(const Scene& scene, const AnalysisParams& p, const StudyControl& control) {
  const std::string path = textOf(p, "parameter");
  const double nominal = parameterValue(scene, path);  // throws invalid_argument naming the path
  withParameter(scene, path, number(p, "from"));
  withParameter(scene, path, number(p, "to"));
  const auto r =
      sensitivitySweep(scene, evaluatorOf(p), path, number(p, "from"), number(p, "to"), integerOf(p, "steps"), control);
  if (!r.ok()) return std::nullopt;
  return sensitivityResultJson(*r.value, path, nominal);
}

std::optional<nlohmann::json> runResolution(const Scene& scene, const AnalysisParams& p) {
  ResolutionOptions o;
  o.samples = integerOf(p, "samples");
  o.gaze_deg = std::array<double, 2>{number(p, "gaze-yaw"), number(p, "gaze-pitch")};
  const ResolutionResult r = analyzeResolution(scene, o);
  if (r.samples.empty()) throw std::runtime_error("no line of sight reaches the HOE or the foveal image for this gaze");
  return resolutionResultJson(r, scene);
}

std::optional<nlohmann::json> runOptimizeLens(const Scene& scene, const AnalysisParams& p,
                                              const StudyControl& control) {
  LensOptimizationOptions o;
  o.starts_per_lens = integerOf(p, "starts");
  const auto r = optimizeBeamShapingLens(scene, defaultLensCatalog(), o, control);
  if (!r.ok()) return std::nullopt;
  return lensOptimizationJson(*r.value);
}

std::optional<nlohmann::json> runSelectivity(const Scene& scene, const AnalysisParams& p) {
  SelectivityOptions o;
  o.point_mm = {number(p, "point-u"), number(p, "point-v")};
  o.angle_span_deg = number(p, "angle-span-deg");
  o.wavelength_span_nm = number(p, "wavelength-span-nm");
  o.angle_samples = o.wavelength_samples = integerOf(p, "samples");
  o.polarization = polarizationOf(p);
  if (scene.hoe_layers.empty()) throw std::runtime_error("the scene has no HOE layer");
  return selectivityResultJson(analyzeSelectivity(scene, o));
}

std::optional<nlohmann::json> runGrating(const AnalysisParams& p, const StudyControl& control) {
  GratingRequest req;
  PlanarGrating& g = req.grating;
  g.film.n0 = number(p, "n0");
  g.film.n1 = number(p, "n1");
  g.film.thickness_um = number(p, "thickness-um");
  g.period_nm = number(p, "period-nm");
  g.slant_deg = number(p, "slant-deg");
  g.probe_deg = number(p, "probe-deg");
  g.wavelength_nm = number(p, "wavelength-nm");
  g.polarization = polarizationOf(p);
  req.absorption_per_mm = number(p, "absorption-per-mm");
  if (auto e = validateGratingRequest(req, false)) throw std::invalid_argument(e->message);
  const bool with_rcwa = textOf(p, "model") == "kogelnik+rcwa";
  const int n = integerOf(p, "samples");
  const double span = number(p, "span-deg"), centre = g.probe_deg;
  nlohmann::json out;
  out["center"] = kogelnikGratingJson(req);
  out["models"] = with_rcwa ? nlohmann::json{"kogelnik", "rcwa"} : nlohmann::json{"kogelnik"};
  nlohmann::json samples = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    if (control.cancelled()) return std::nullopt;
    const double probe = centre - span + 2.0 * span * i / std::max(1, n - 1);
    nlohmann::json s{{"probe_deg", probe}, {"detuning_deg", probe - centre}};
    GratingRequest r = req;
    r.grating.probe_deg = probe;
    if (std::abs(probe) >= 90.0 || validateGratingRequest(r, false)) {
      s["kogelnik_efficiency"] = nullptr;
    } else {
      const nlohmann::json k = kogelnikGratingJson(r);
      s["kogelnik_efficiency"] = k["efficiency"];
      s["xi"] = k["xi"];
      s["nu"] = k["nu"];
    }
    if (with_rcwa) {
      rigorous::RcwaGratingRequest rr;
      rr.n0 = g.film.n0;
      rr.n1 = g.film.n1;
      rr.thickness_um = g.film.thickness_um;
      rr.period_nm = g.period_nm;
      rr.slant_deg = g.slant_deg;
      rr.probe_deg = probe;
      rr.wavelength_nm = g.wavelength_nm;
      rr.absorption_per_mm = req.absorption_per_mm;
      rr.polarization = g.polarization == Polarization::S   ? rigorous::GratingPolarization::S
                        : g.polarization == Polarization::P ? rigorous::GratingPolarization::P
                                                            : rigorous::GratingPolarization::Unpolarized;
      try {
        const auto a = rigorous::solveRcwaGrating(rr);
        s["rcwa_efficiency"] = a.efficiency;
        s["rcwa_converged"] = a.converged;
      } catch (const std::exception&) {
        s["rcwa_efficiency"] = nullptr;
      }
    }
    samples.push_back(s);
    if (control.on_progress) control.on_progress(double(i + 1) / n);
  }
  out["samples"] = samples;
  return out;
}

std::optional<nlohmann::json> runKogelnikVsRcwa(const AnalysisParams& p, const StudyControl& control) {
  const rigorous::KogelnikRcwaGrid grid =
      textOf(p, "grid") == "full" ? rigorous::KogelnikRcwaGrid{} : rigorous::KogelnikRcwaGrid::quick();
  // One geometry at a time, so that Cancel is honoured between them.
  std::vector<rigorous::KogelnikRcwaPoint> all;
  const auto n = grid.geometries.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (control.cancelled()) return std::nullopt;
    rigorous::KogelnikRcwaGrid one = grid;
    one.geometries = {grid.geometries[i]};
    auto pts = rigorous::kogelnikVsRcwa(one);
    all.insert(all.end(), pts.begin(), pts.end());
    if (control.on_progress) control.on_progress(double(i + 1) / n);
  }
  if (control.cancelled()) return std::nullopt;
  nlohmann::json j = kogelnikVsRcwaJson(all);
  j["grid"] = textOf(p, "grid");
  return j;
}

bool cachedStudy(const QString& id) {
  return id == "sweep" || id == "compare-shift" || id == "sensitivity" || id == "optimize-lens";
}

}  // namespace

const QList<AnalysisSpec>& analysisCatalog() {
  static const QList<AnalysisSpec> catalog = buildCatalog();
  return catalog;
}

const AnalysisSpec* findAnalysis(const QString& id) {
  for (const AnalysisSpec& s : analysisCatalog())
    if (s.id == id) return &s;
  return nullptr;
}

AnalysisParams defaultParameters(const AnalysisSpec& spec, int defaultRays) {
  AnalysisParams p;
  for (const AnalysisParameter& a : spec.parameters) p.insert(a.key, a.defaultValue);
  if (defaultRays > 0 && p.contains("rays")) p["rays"] = defaultRays;
  return p;
}

QStringList validateParameters(const AnalysisSpec& spec, AnalysisParams& params) {
  QStringList problems;
  for (const AnalysisParameter& a : spec.parameters) {
    if (!params.contains(a.key)) params.insert(a.key, a.defaultValue);
    const QVariant v = params.value(a.key);
    switch (a.kind) {
      case Kind::Number:
      case Kind::Integer: {
        bool ok = false;
        const double x = v.toDouble(&ok);
        if (!ok || !std::isfinite(x))
          problems << QStringLiteral("%1: not a number (\"%2\")").arg(a.key, v.toString());
        else if (x < a.minimum || x > a.maximum)
          problems
              << QStringLiteral("%1: must lie in %2 .. %3, got %4").arg(a.key).arg(a.minimum).arg(a.maximum).arg(x);
        else if (a.kind == Kind::Integer && std::floor(x) != x)
          problems << QStringLiteral("%1: must be a whole number, got %2").arg(a.key).arg(x);
        else
          params[a.key] = a.kind == Kind::Integer ? QVariant(int(x)) : QVariant(x);
        break;
      }
      case Kind::Choice:
        if (!a.choices.contains(v.toString()))
          problems
              << QStringLiteral("%1: expected one of %2, got \"%3\"").arg(a.key, a.choices.join(", "), v.toString());
        break;
      case Kind::Text:
        if (v.toString().trimmed().isEmpty()) problems << QStringLiteral("%1: must not be empty").arg(a.key);
        params[a.key] = v.toString().trimmed();
        break;
    }
  }
  return problems;
}

QString cliCommandLine(const AnalysisSpec& spec, const AnalysisParams& params, const QString& scenePath) {
  if (!spec.hasCliTwin) return {};
  auto arg = [&](const QString& k) {
    const QVariant v = params.value(k);
    return v.typeId() == QMetaType::Double ? QString::number(v.toDouble(), 'g', 10) : v.toString();
  };
  QStringList a{"fovea-cli", spec.id};
  if (spec.id != "grating") a << (scenePath.isEmpty() ? QStringLiteral("\"\"") : scenePath);
  QStringList skip;
  if (spec.id == "trace" || spec.id == "resolution") {
    a << "--gaze-deg" << arg("gaze-yaw") + "," + arg("gaze-pitch");
    skip << "gaze-yaw"
         << "gaze-pitch";
  }
  if (spec.id == "trace") {
    a << "--hoe-shift-mm" << arg("hoe-shift-x") + "," + arg("hoe-shift-y");
    skip << "hoe-shift-x"
         << "hoe-shift-y";
    if (params.value("wavelength-nm").toDouble() <= 0) skip << "wavelength-nm";
  }
  if (spec.id == "selectivity") {
    a << "--point-mm" << arg("point-u") + "," + arg("point-v");
    skip << "point-u"
         << "point-v";
  }
  if (spec.id == "grating")
    skip << "span-deg"
         << "samples"
         << "model";  // the CLI answers one probe angle
  for (const AnalysisParameter& p : spec.parameters) {
    if (skip.contains(p.key)) continue;
    QString v = arg(p.key);
    if (v.contains(' ') || v.contains('[')) v = '"' + v + '"';
    a << "--" + p.key << v;
  }
  a << "--json";
  return a.join(' ');
}

std::optional<nlohmann::json> runAnalysis(const QString& id, const Scene& scene, const AnalysisParams& params,
                                          const StudyControl& control) {
  const AnalysisSpec* spec = findAnalysis(id);
  if (!spec) throw std::invalid_argument("unknown analysis '" + id.toStdString() + "'");
  AnalysisParams p = params;
  const QStringList problems = validateParameters(*spec, p);
  if (!problems.isEmpty()) throw std::invalid_argument(problems.join("; ").toStdString());
  if (control.cancelled()) return std::nullopt;

  std::string key;
  if (cachedStudy(id)) {
    key = StudyCache::makeKey("studio:" + id.toStdString(), paramsJson(p), serializeScene(scene));
    if (auto hit = StudyCache::global().find(key)) {
      (*hit)["cached"] = true;
      if (control.on_progress) control.on_progress(1.0);
      return hit;
    }
  }
  std::optional<nlohmann::json> out;
  if (id == "trace")
    out = runTrace(scene, p);
  else if (id == "sweep")
    out = runSweep(scene, p, control);
  else if (id == "compare-shift")
    out = runCompareShift(scene, p, control);
  else if (id == "sensitivity")
    out = runSensitivity(scene, p, control);
  else if (id == "resolution")
    out = runResolution(scene, p);
  else if (id == "optimize-lens")
    out = runOptimizeLens(scene, p, control);
  else if (id == "selectivity")
    out = runSelectivity(scene, p);
  else if (id == "grating")
    out = runGrating(p, control);
  else if (id == "kogelnik-vs-rcwa")
    out = runKogelnikVsRcwa(p, control);
  if (!out || control.cancelled()) return std::nullopt;
  if (!key.empty()) StudyCache::global().store(key, *out);
  (*out)["cached"] = false;
  if (control.on_progress) control.on_progress(1.0);
  return out;
}

}  // namespace fovea::widgets
