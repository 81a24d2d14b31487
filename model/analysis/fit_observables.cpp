#include "model/analysis/fit_observables.h"

#include "model/scene/scene_fields.h"  // Range

#include <cmath>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "model/analysis/analysis_parameters.h"
#include "model/analysis/angular_resolution.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/eyebox_walk.h"
#include "model/analysis/trace_evaluator.h"

namespace fovea {

namespace {

std::string keyOf(std::initializer_list<double> numbers, const std::string& text) {
  std::string k = text;
  for (const double x : numbers) k += "|" + std::to_string(x);
  return k;
}

std::string laserKey(std::optional<double> wavelength_nm) {
  return wavelength_nm ? std::to_string(*wavelength_nm) : std::string("all");
}

}  // namespace

const FovEvaluator& ObservableContext::evaluator(std::optional<double> wavelength_nm) {
  const std::string k = laserKey(wavelength_nm);
  std::lock_guard lock(mutex_);
  auto it = evaluators_.find(k);
  if (it == evaluators_.end()) {
    TraceEvaluatorOptions o;
    o.fov_method = FovMethod::Edges;
    o.edge_tolerance_deg = settings_.fov_tolerance_deg;
    o.wavelength_nm = wavelength_nm;
    it = evaluators_.emplace(k, traceEvaluator(o)).first;
  }
  return it->second;
}

// The slot of a key, created under the lock; its value computed once (std::call_once: a
// concurrent caller waits for it, a throw leaves it for the next caller). Isolated, so that
// while it waits on nested parallel work this thread never picks up a task that would wait
// on this very slot (oneTBB's this_task_arena::isolate).
template <class T, class Compute>
const T& ObservableContext::once(std::map<std::string, std::unique_ptr<Once<T>>>& memo, const std::string& key,
                                 Compute&& compute) {
  Once<T>* slot = nullptr;
  {
    std::lock_guard lock(mutex_);
    auto& p = memo[key];
    if (!p) p = std::make_unique<Once<T>>();
    slot = p.get();
  }
  std::call_once(slot->flag, [&] { tbb::this_task_arena::isolate([&] { slot->value.emplace(compute()); }); });
  return *slot->value;
}

const GazeSample& ObservableContext::optimalShift(double gaze_deg, GazeAxis axis, ShiftMethod method,
                                                  std::optional<double> wavelength_nm,
                                                  const GazeStudyOptions& options) {
  const std::string k =
      keyOf({gaze_deg, double(axis), double(method), options.plateau_tolerance_deg, double(options.xp_rule)},
            laserKey(wavelength_nm));
  return once(shifts_, k,
              [&] { return optimiseShift(scene_, evaluator(wavelength_nm), gaze_deg, axis, method, options); });
}

const EyeBox& ObservableContext::eyeBox(double from_deg, double to_deg, double step_deg, GazeAxis axis,
                                        ShiftMethod method, std::optional<double> wavelength_nm,
                                        const GazeStudyOptions& options) {
  const std::string k = keyOf(
      {from_deg, to_deg, step_deg, double(axis), double(method), options.tolerance_deg, double(options.criterion)},
      laserKey(wavelength_nm));
  return once(eyeboxes_, k, [&] {
    return walkEyeBox(sweepGazes(from_deg, to_deg, step_deg), axis, options,
                      [&](double gaze_deg) { return optimalShift(gaze_deg, axis, method, wavelength_nm, options); });
  });
}

namespace {

// Parameter readers (values validated by completeObservableParameters).
double num(const nlohmann::json& p, const char* k) {
  return p.at(k).get<double>();
}
std::string txt(const nlohmann::json& p, const char* k) {
  return p.at(k).get<std::string>();
}
std::optional<double> laser(const nlohmann::json& p) {
  return p.at("wavelength_nm").is_null() ? std::nullopt : std::optional<double>(p.at("wavelength_nm").get<double>());
}
GazeAxis axisOf(const nlohmann::json& p) {
  return txt(p, "axis") == "pitch" ? GazeAxis::Pitch : GazeAxis::Yaw;
}
ShiftMethod methodOf(const nlohmann::json& p) {
  const std::string m = txt(p, "method");
  if (m == "source") return ShiftMethod::Source;
  if (m == "source_axial") return ShiftMethod::SourceAxial;
  return m == "none" ? ShiftMethod::None : ShiftMethod::Hoe;
}

GazeStudyOptions studyOptions(const ObservableContext& ctx, const nlohmann::json& p) {
  GazeStudyOptions o;
  o.edge_bisections = ctx.settings().shift_bisections;
  o.border_bisections = ctx.settings().border_bisections;
  if (p.contains("tolerance_deg")) o.tolerance_deg = num(p, "tolerance_deg");
  if (p.contains("plateau_tolerance_deg")) o.plateau_tolerance_deg = num(p, "plateau_tolerance_deg");
  if (p.contains("criterion") && txt(p, "criterion") == "centre-fov") o.criterion = EyeBoxCriterion::CentreFov;
  if (p.contains("xp_rule")) o.xp_rule = parseXpRule(txt(p, "xp_rule")).value_or(XpRule::PlateauMiddle);
  return o;
}

// The FOV sample at a gaze with the HOE (or source) at x_p, at a fixed shift, or unmoved.
FovSample fovAt(ObservableContext& ctx, const nlohmann::json& p) {
  const double gaze = num(p, "gaze_deg");
  const GazeAxis axis = axisOf(p);
  const std::string shift = txt(p, "shift");
  ShiftMethod method = methodOf(p);
  if (shift == "optimal") {
    if (method == ShiftMethod::None) throw std::invalid_argument("shift \"optimal\" needs method hoe or source");
    return ctx.optimalShift(gaze, axis, method, laser(p), studyOptions(ctx, p)).fov;
  }
  const double s = shift == "fixed" ? num(p, "shift_mm") : 0.0;
  if (shift == "none") method = ShiftMethod::None;
  return ctx.evaluator(laser(p))(ctx.scene(), gazeQuery(gaze, axis, method, s));
}

const EyeBox& eyeBoxOf(ObservableContext& ctx, const nlohmann::json& p) {
  if (!(num(p, "gaze_to") > num(p, "gaze_from")) || !(num(p, "gaze_step") > 0) ||
      (num(p, "gaze_to") - num(p, "gaze_from")) / num(p, "gaze_step") > analysis::kMaxGazeSamples)
    throw std::invalid_argument("gaze_from < gaze_to and 0 < gaze_step with at most " +
                                std::to_string(analysis::kMaxGazeSamples) + " samples");
  return ctx.eyeBox(num(p, "gaze_from"), num(p, "gaze_to"), num(p, "gaze_step"), axisOf(p), methodOf(p), laser(p),
                    studyOptions(ctx, p));
}

std::size_t endIndex(const nlohmann::json& p) {
  return txt(p, "end") == "lower" ? 0 : 1;
}

// Linear interpolation of an optional curve at x (the two samples around x must exist).
double interpolateAt(const std::vector<ResolutionSample>& s, double x,
                     std::optional<double> (*value)(const ResolutionSample&), const std::string& what) {
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    if (x < s[i].eccentricity_deg || x > s[i + 1].eccentricity_deg) continue;
    const auto a = value(s[i]), b = value(s[i + 1]);
    if (!a || !b) break;
    const double t = (x - s[i].eccentricity_deg) / (s[i + 1].eccentricity_deg - s[i].eccentricity_deg);
    return *a + t * (*b - *a);
  }
  throw std::runtime_error("no " + what + " resolution at eccentricity " + std::to_string(x) + " deg");
}

ObservableParameter gazeParam() {
  return {"gaze_deg", 0.0, {}, "gaze angle along `axis` (deg)"};
}
ObservableParameter axisParam() {
  return {"axis", "yaw", {"yaw", "pitch"}, "yaw: horizontal (HOE local x); pitch: vertical (HOE local y)"};
}
ObservableParameter xpRuleParam() {
  return {"xp_rule",
          "plateau-middle",
          {"plateau-middle", "follow-focus"},
          "how x_p is chosen (method hoe): the middle of the FOV plateau, or the diffracted rays' focus on the rotated "
          "pupil centre (the seed's; gaze_studies.h)"};
}
ObservableParameter laserParam() {
  return {"wavelength_nm", nullptr, {}, "trace only the laser at this wavelength (null: every projector laser)"};
}
std::vector<ObservableParameter> shiftParams() {
  return {{"shift",
           "optimal",
           {"optimal", "fixed", "none"},
           "optimal: the HOE (or source) at x_p of the gaze; fixed: at shift_mm; none: unmoved"},
          {"shift_mm", 0.0, {}, "the shift with shift \"fixed\" (mm)"},
          {"method",
           "hoe",
           {"hoe", "source", "source_axial"},
           "what moves: the HOE laterally, the point source along bench z, or along the projector's axis (the seed's "
           "z_s)"},
          {"plateau_tolerance_deg", 5.0, {}, "x_p plateau: FOV within this of the best (gaze_studies.h)"},
          xpRuleParam()};
}
std::vector<ObservableParameter> sweepParams(bool with_end) {
  std::vector<ObservableParameter> v{
      {"method",
       "hoe",
       {"hoe", "source", "source_axial", "none"},
       "what moves with the gaze (none: the static eye box)"},
      axisParam(),
      {"criterion",
       "tolerance",
       {"tolerance", "centre-fov"},
       "eye box: FOV >= FOV(0) - tolerance_deg, or the seed's FOV >= FOV(0) (A.3; gaze_studies.h)"},
      {"tolerance_deg", 3.0, {}, "eye-box criterion tolerance: FOV >= FOV(0) - tolerance_deg"},
      {"gaze_from", -40.0, {}, "first gaze of the sweep (deg)"},
      {"gaze_to", 40.0, {}, "last gaze of the sweep (deg)"},
      {"gaze_step", 5.0, {}, "coarse gaze step before the borders are bisected (deg)"},
      laserParam()};
  if (with_end) v.push_back({"end", "upper", {"lower", "upper"}, "which border"});
  return v;
}

std::vector<ObservableDefinition> buildTable() {
  std::vector<ObservableDefinition> t;
  {
    ObservableDefinition d{
        "fov_deg",
        "deg",
        "continuous retinal FOV at a gaze (edge estimator, fov_edges.h), smallest over the lasers",
        {gazeParam(), axisParam(), {"direction", "horizontal", {"horizontal", "vertical", "diagonal"}, "which FOV"}},
        nullptr};
    for (auto& s : shiftParams()) d.parameters.push_back(s);
    d.parameters.push_back(laserParam());
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json& p) {
      const FovSample f = fovAt(ctx, p);
      const std::string dir = txt(p, "direction");
      return dir == "vertical" ? f.vertical_deg : dir == "diagonal" ? f.diagonal_deg : f.horizontal_deg;
    };
    t.push_back(d);
  }
  {
    ObservableDefinition d{"mean_efficiency",
                           "",
                           "mean diffraction efficiency of the rays in the pupil at a gaze",
                           {gazeParam(), axisParam()},
                           nullptr};
    for (auto& s : shiftParams()) d.parameters.push_back(s);
    d.parameters.push_back(laserParam());
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json& p) { return fovAt(ctx, p).mean_efficiency; };
    t.push_back(d);
  }
  {
    ObservableDefinition d{
        "x_p_mm",
        "mm",
        "travel at a gaze: the HOE shift x_p (method hoe) or the source shift z_s along bench z "
        "(method source) that maximises the FOV (gaze_studies.h optimiseShift; xp_rule picks the HOE's rule)",
        {gazeParam(),
         axisParam(),
         {"method", "hoe", {"hoe", "source", "source_axial"}, "what moves"},
         {"plateau_tolerance_deg", 5.0, {}, "x_p plateau: FOV within this of the best"},
         xpRuleParam(),
         laserParam()},
        nullptr};
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json& p) {
      return ctx.optimalShift(num(p, "gaze_deg"), axisOf(p), methodOf(p), laser(p), studyOptions(ctx, p)).shift_mm;
    };
    t.push_back(d);
  }
  {
    ObservableDefinition d{"eyebox_mm", "mm",
                           "eye-box width: pupil-centre range around zero gaze whose FOV stays within tolerance_deg "
                           "of the zero-gaze FOV (gaze_studies.h sweepGaze)",
                           sweepParams(false), nullptr};
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json& p) { return eyeBoxOf(ctx, p).width_mm; };
    t.push_back(d);
  }
  {
    ObservableDefinition d{"gaze_coverage_deg", "deg", "gaze angle at a border of the eye box of a method",
                           sweepParams(true), nullptr};
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json& p) {
      return eyeBoxOf(ctx, p).gaze_range_deg[endIndex(p)];
    };
    t.push_back(d);
  }
  {
    ObservableDefinition d{"eyebox_travel_mm", "mm",
                           "travel (x_p or z_s) at a border of the eye box of a method (seed A.4: z_s +5.6 ... -6.3)",
                           sweepParams(true), nullptr};
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json& p) {
      return eyeBoxOf(ctx, p).travel_mm[endIndex(p)];
    };
    t.push_back(d);
  }
  {
    ObservableDefinition d{
        "cpd",
        "cpd",
        "angular resolution at an eccentricity for a gaze (angular_resolution.h)",
        {{"eccentricity_deg", 0.0, {}, "eccentricity from the line of sight (deg, + towards +yaw)"},
         {"gaze_deg", 0.0, {}, "gaze yaw (deg)"},
         {"kind", "perceived", {"perceived", "peripheral", "foveal", "optical_limit"}, "which resolution"}},
        nullptr};
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json& p) {
      ResolutionOptions o;
      o.gaze_deg = std::array<double, 2>{num(p, "gaze_deg"), 0.0};
      const ResolutionResult r = analyzeResolution(ctx.scene(), o);
      const std::string kind = txt(p, "kind");
      std::optional<double> (*value)(const ResolutionSample&) = [](const ResolutionSample& s) {
        return std::optional<double>(s.perceived_cpd);
      };
      if (kind == "peripheral") value = [](const ResolutionSample& s) { return s.peripheral_cpd; };
      if (kind == "foveal") value = [](const ResolutionSample& s) { return s.foveal_cpd; };
      if (kind == "optical_limit") value = [](const ResolutionSample& s) { return s.optical_limit_cpd; };
      return interpolateAt(r.samples, num(p, "eccentricity_deg"), value, kind);
    };
    t.push_back(d);
  }
  {
    ObservableDefinition d{"rms_spot_um",
                           "um",
                           "RMS pixel spot on the HOE of the unshaped beam, over the pixel grid and the lasers "
                           "(beam_shaping.h evaluateSpots; the scene's pixel-beam model, no lens)",
                           {},
                           nullptr};
    d.evaluate = [](ObservableContext& ctx, const nlohmann::json&) {
      return evaluateSpots(ctx.scene(), std::nullopt).rms_spot_um;
    };
    t.push_back(d);
  }
  return t;
}

}  // namespace

const std::vector<ObservableDefinition>& observableTable() {
  static const std::vector<ObservableDefinition> table = buildTable();
  return table;
}

const ObservableDefinition* findObservable(const std::string& name) {
  for (const auto& d : observableTable())
    if (d.name == name) return &d;
  return nullptr;
}

std::string observableNames() {
  std::string s;
  for (const auto& d : observableTable()) s += (s.empty() ? "" : ", ") + d.name;
  return s;
}

nlohmann::json completeObservableParameters(const ObservableDefinition& def, const nlohmann::json& given) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : given.items()) {
    const ObservableParameter* spec = nullptr;
    for (const auto& p : def.parameters)
      if (p.name == key) spec = &p;
    if (!spec) {
      std::string names;
      for (const auto& p : def.parameters) names += (names.empty() ? "" : ", ") + p.name;
      throw std::invalid_argument(key + ": not a parameter of " + def.name +
                                  (names.empty() ? " (it takes none)" : " (its parameters: " + names + ")"));
    }
    if (!spec->choices.empty()) {
      bool ok = value.is_string();
      if (ok) {
        ok = false;
        for (const auto& c : spec->choices) ok = ok || value.get<std::string>() == c;
      }
      if (!ok) {
        std::string list;
        for (const auto& c : spec->choices) {
          if (!list.empty()) list += ", ";
          list += c;
        }
        throw std::invalid_argument(
            std::string(key).append(": must be one of ").append(list).append(", got ").append(value.dump()));
      }
    } else if (!(value.is_number() && std::isfinite(value.get<double>())) &&
               !(value.is_null() && spec->default_value.is_null())) {
      throw std::invalid_argument(key + ": must be a finite number, got " + value.dump());
    }
    out[key] = value;
  }
  for (const auto& p : def.parameters)
    if (!out.contains(p.name)) out[p.name] = p.default_value;
  for (const char* angle : {"gaze_deg", "eccentricity_deg", "gaze_from", "gaze_to"})
    if (out.contains(angle) && std::abs(out[angle].get<double>()) > analysis::kGazeLimitDeg)
      throw std::invalid_argument(std::string(angle) + ": must lie in [-80, 80] deg, got " + out[angle].dump());
  // The other numbers' ranges: those of the CLI options and the scene that they stand for
  // (trace's --wavelength-nm, the sweep's --gaze-step, the eye-box tolerance).
  const std::pair<const char*, Range> ranges[] = {
      {"wavelength_nm", Range::openClosed(0, 2000)}, {"gaze_step", Range::openClosed(0, 160)},
      {"tolerance_deg", Range::openClosed(0, 90)},   {"plateau_tolerance_deg", Range::openClosed(0, 90)},
      {"shift_mm", Range::closed(-1000, 1000)},
  };
  for (const auto& [key, range] : ranges)
    if (out.contains(key) && out[key].is_number())
      if (const std::string p = range.check(out[key].get<double>()); !p.empty())
        throw std::invalid_argument(std::string(key) + ": " + p);
  return out;
}

}  // namespace fovea
