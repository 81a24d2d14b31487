#include "app/studio/report_data.h"

#include <QRegularExpression>

#include <algorithm>
#include <cmath>

#include "model/analysis/hoe_travel.h"
#include "model/color/srgb.h"
#include "model/image/foveation.h"
#include "model/image/retina_image.h"
#include "model/image/retina_image_figures.h"
#include "model/image/test_target.h"
#include "model/physics/projector_rays.h"
#include "model/scene/eye_scene.h"
#include "widgets/analyses/analysis_catalog.h"

namespace fovea::studio {

using widgets::AnalysisParams;
using widgets::defaultParameters;
using widgets::findAnalysis;
using widgets::runAnalysis;

bool parseGaze(const QString& text, std::array<double, 2>* gaze) {
  const QStringList parts = text.trimmed().split(',');
  if (parts.isEmpty() || parts.size() > 2) return false;
  std::array<double, 2> g{0, 0};
  for (int i = 0; i < parts.size(); ++i) {
    bool ok = false;
    g[i] = parts[i].trimmed().toDouble(&ok);
    if (!ok || !std::isfinite(g[i]) || std::abs(g[i]) > 90) return false;
  }
  *gaze = g;
  return true;
}

namespace {

// Runs one catalogue analysis as part of the report: progress mapped into [from, to).
std::optional<nlohmann::json> step(const QString& id, const Scene& scene, AnalysisParams params,
                                   const StudyControl& control, double from, double to, QStringList& problems,
                                   bool* cancelled) {
  StudyControl sub;
  sub.cancel = control.cancel;
  if (control.on_progress) sub.on_progress = [&](double f) { control.on_progress(from + (to - from) * f); };
  try {
    auto r = runAnalysis(id, scene, params, sub);
    if (!r) *cancelled = true;
    return r;
  } catch (const std::exception& e) {
    problems << QString("%1: %2").arg(id, QString::fromUtf8(e.what()));
    return std::nullopt;
  }
}

// The accommodations of the report's resolution sweep (0.4..3.3 D: the seed's 250..30 cm, C.3).
constexpr const char* kReportAccommodationsD = "0.4,0.67,1,1.25,1.67,2.5,3.3";
// The report's retinal image: the test target at 960 px (as the preview's Retina image mode),
// the eye focused on the foveal image (1 / its distance).
constexpr int kReportRetinaWidthPx = 960;

std::optional<ReportRetinaImage> reportRetinaImage(const Scene& scene, std::array<double, 2> gaze_deg,
                                                   std::array<double, 2> hoe_shift_mm, const ReportOptions& options,
                                                   QStringList& problems) {
  try {
    const image::DisplayAngles a = image::displayAngles(scene);
    const cv::Size size(kReportRetinaWidthPx,
                        std::max(1, static_cast<int>(std::lround(kReportRetinaWidthPx * a.peripheral_fov_deg[1] /
                                                                 a.peripheral_fov_deg[0]))));
    const cv::Mat target = image::makeTestTarget(size, a.peripheral_fov_deg, 20.0);
    image::RetinaImageOptions o;
    o.gaze_deg = gaze_deg;
    const double d_f = scene.foveal_display.combiner.image_distance_mm;
    o.accommodation_d = d_f > 250 ? std::clamp(1000.0 / d_f, 0.0, 4.0) : 1.25;
    o.hoe_shift_mm = hoe_shift_mm;
    o.speckle_patterns = options.retina.speckle_patterns;
    o.speckle_grain_pupil = options.retina.speckle_grain_pupil;
    o.per_laser_calibration = options.retina.per_laser_calibration;
    o.speckle_seed = static_cast<std::uint64_t>(options.retina.speckle_seed);
    const image::RetinaImageResult r = image::renderRetinaImage(scene, target, o);
    ReportRetinaImage out;
    out.options = o;
    out.speckle_contrast = r.speckle_contrast;
    out.speckle_expected = r.speckle_expected;
    out.lateral_colour_arcmin = image::lateralColourShownArcmin(r, o);
    out.power_in_pupil = r.power_in_pupil;
    out.power_on_retina = r.power_on_retina;
    if (!r.peripheral.empty() && r.peripheral[r.peripheral_reference].valid) {
      out.peripheral_spot_arcmin = r.peripheral[r.peripheral_reference].metrics.fwhm_arcmin;
      out.peripheral_mtf50_cpd = r.peripheral[r.peripheral_reference].metrics.mtf50_cpd;
    }
    if (!r.foveal.empty()) {
      out.foveal_spot_arcmin = r.foveal[r.foveal_reference].metrics.fwhm_arcmin;
      out.foveal_mtf50_cpd = r.foveal[r.foveal_reference].metrics.mtf50_cpd;
    }
    QImage img(r.image.cols, r.image.rows, QImage::Format_RGB888);
    for (int y = 0; y < r.image.rows; ++y) {
      const auto* in = r.image.ptr<cv::Vec3f>(y);
      uchar* line = img.scanLine(y);
      for (int x = 0; x < r.image.cols; ++x)
        for (int c = 0; c < 3; ++c)
          line[3 * x + c] =
              static_cast<uchar>(std::lround(255.0F * color::linearToSrgb(std::clamp(in[x][c], 0.0F, 1.0F))));
    }
    out.image = img;
    return out;
  } catch (const std::exception& e) {
    problems << QString("retina image: %1").arg(QString::fromUtf8(e.what()));
    return std::nullopt;
  }
}

}  // namespace

std::optional<ReportData> computeReportData(const Scene& loaded, const QString& scenePath, ReportOptions options,
                                            const StudyControl& outer) {
  // A binocular scene: the analyses run on one eye's train (eye_scene.h), the right's unless "left".
  const bool leftOnly = loaded.binocular && options.eye == "left";
  const bool bothEyes = loaded.binocular && !leftOnly && options.eye != "right";
  const bool gazesGiven = !options.gazes_deg.isEmpty();
  const Scene scene = loaded.binocular ? eyeScene(loaded, leftOnly ? EyeSide::Left : EyeSide::Right) : loaded;
  // With the tolerance analysis the other analyses take the first 60 % of the progress.
  const double share = options.tolerance ? 0.6 : 1.0;
  StudyControl control;
  control.cancel = outer.cancel;
  if (outer.on_progress) control.on_progress = [&outer, share](double f) { outer.on_progress(share * f); };
  ReportData d;
  d.scene = leftOnly ? scene : loaded;
  d.scenePath = scenePath;
  if (loaded.binocular && !bothEyes) d.eye = leftOnly ? "left" : "right";
  if (options.gazes_deg.isEmpty()) options.gazes_deg = {scene.eye.gaze_deg};
  d.options = options;
  bool cancelled = false;
  auto progress = [&](double f) {
    if (control.on_progress) control.on_progress(std::min(1.0, f));
  };

  // Traces at the chosen gazes (20 %).
  const int n = static_cast<int>(options.gazes_deg.size());
  for (int i = 0; i < n; ++i) {
    if (control.cancelled()) return std::nullopt;
    GazeTrace t;
    t.gaze_deg = options.gazes_deg[i];
    if (options.follow_gaze) {
      // The one x_p source (hoe_travel.h), as the live trace, the capture plan and the bench.
      try {
        t.hoe_shift_mm = hoeTravel(scene, t.gaze_deg, sceneXpRule(scene)).shift_mm;
      } catch (const std::exception& e) {
        d.problems << QString("HOE shift at gaze %1,%2: %3").arg(t.gaze_deg[0]).arg(t.gaze_deg[1]).arg(e.what());
        t.hoe_shift_mm = {0, 0};
      }
    }
    AnalysisParams p = defaultParameters(*findAnalysis("trace"), options.rays);
    p["gaze-yaw"] = t.gaze_deg[0];
    p["gaze-pitch"] = t.gaze_deg[1];
    p["hoe-shift-x"] = t.hoe_shift_mm[0];
    p["hoe-shift-y"] = t.hoe_shift_mm[1];
    auto j = step("trace", scene, p, control, 0.2 * i / n, 0.2 * (i + 0.5) / n, d.problems, &cancelled);
    if (cancelled) return std::nullopt;
    if (!j) continue;
    t.json = *j;
    TraceOptions o;
    o.gaze_deg = t.gaze_deg;
    o.rays = options.rays;
    o.hoe_shift_mm = t.hoe_shift_mm;
    o.keep_rays = true;
    t.rays = traceScene(scene, o);
    t.grid = projectorGrid(scene.projector, o.rays);
    d.traces << t;
    progress(0.2 * (i + 1) / n);
  }

  // Both eyes of a binocular scene: each eye's trace at the chosen gazes (each eye's own gaze
  // when none was chosen), with its x_p.
  if (bothEyes) {
    d.eyes = nlohmann::json::object();
    for (const EyeSide side : {EyeSide::Left, EyeSide::Right}) {
      const Scene es = eyeScene(loaded, side);
      const QList<std::array<double, 2>> gazes = gazesGiven ? options.gazes_deg : QList{es.eye.gaze_deg};
      nlohmann::json list = nlohmann::json::array();
      for (const auto& gaze : gazes) {
        if (control.cancelled()) return std::nullopt;
        std::array<double, 2> xp{NAN, NAN};
        try {
          xp = hoeTravel(es, gaze, sceneXpRule(es)).shift_mm;
        } catch (const std::exception& e) {
          d.problems << QString("%1 eye: HOE shift at gaze %2,%3: %4")
                            .arg(eyeSideName(side))
                            .arg(gaze[0])
                            .arg(gaze[1])
                            .arg(e.what());
        }
        const std::array<double, 2> shift =
            options.follow_gaze && std::isfinite(xp[0]) ? xp : std::array<double, 2>{0, 0};
        AnalysisParams p = defaultParameters(*findAnalysis("trace"), options.rays);
        p["gaze-yaw"] = gaze[0];
        p["gaze-pitch"] = gaze[1];
        p["hoe-shift-x"] = shift[0];
        p["hoe-shift-y"] = shift[1];
        QStringList problems;
        auto j = step("trace", es, p, control, 0.2, 0.2, problems, &cancelled);
        if (cancelled) return std::nullopt;
        for (const QString& problem : problems) d.problems << QString("%1 eye: %2").arg(eyeSideName(side), problem);
        if (!j) continue;
        list.push_back({{"gaze_deg", {gaze[0], gaze[1]}},
                        {"fov_deg", j->value("fov_deg", nlohmann::json())},
                        {"mean_efficiency", j->value("mean_efficiency", nlohmann::json())},
                        {"x_p_mm", std::isfinite(xp[0]) ? nlohmann::json{xp[0], xp[1]} : nlohmann::json()},
                        {"hoe_shift_mm", {shift[0], shift[1]}}});
      }
      d.eyes[eyeSideName(side)] = {{"gazes", list}};
    }
  }

  // Gaze sweep over the scene's design gaze range (40 %).
  AnalysisParams sweep = defaultParameters(*findAnalysis("sweep"), options.rays);
  double lo = std::min(scene.eye.gaze_range_deg[0], scene.eye.gaze_range_deg[1]);
  double hi = std::max(scene.eye.gaze_range_deg[0], scene.eye.gaze_range_deg[1]);
  if (!(hi > lo)) lo = -20, hi = 20;
  sweep["gaze-from"] = lo;
  sweep["gaze-to"] = hi;
  sweep["gaze-step"] = std::max(0.5, options.sweep_step_deg);
  if (auto j = step("sweep", scene, sweep, control, 0.2, bothEyes ? 0.5 : 0.6, d.problems, &cancelled)) d.sweep = *j;
  if (cancelled) return std::nullopt;
  // Both eyes: each eye's eye box over the same gaze range (the left eye's own sweep: its own
  // train in mode "explicit", the mirror image in mode "mirror", where it equals the right's).
  if (bothEyes) {
    auto eyeBox = [](const nlohmann::json& j) {
      return nlohmann::json{{"eyebox_mm", j.value("eyebox_mm", nlohmann::json())},
                            {"eyebox", j.value("eyebox", nlohmann::json())}};
    };
    if (!d.sweep.is_null()) d.eyes["right"].update(eyeBox(d.sweep));
    QStringList problems;
    if (auto j = step("sweep", eyeScene(loaded, EyeSide::Left), sweep, control, 0.5, 0.6, problems, &cancelled))
      d.eyes["left"].update(eyeBox(*j));
    for (const QString& problem : problems) d.problems << QString("left eye: %1").arg(problem);
    if (cancelled) return std::nullopt;
  }

  // Resolution at the first gaze (10 %), selectivity (5 %).
  AnalysisParams res = defaultParameters(*findAnalysis("resolution"));
  res["gaze-yaw"] = options.gazes_deg.front()[0];
  res["gaze-pitch"] = options.gazes_deg.front()[1];
  res["accommodation-d"] = kReportAccommodationsD;  // the resolution-vs-accommodation plot
  if (auto j = step("resolution", scene, res, control, 0.6, 0.7, d.problems, &cancelled)) d.resolution = *j;
  if (cancelled) return std::nullopt;
  // The retinal image at the first gaze, with the HOE where its trace had it (x_p when following).
  std::array<double, 2> retinaShift{0, 0};
  for (const GazeTrace& t : d.traces)
    if (t.gaze_deg == options.gazes_deg.front()) {
      retinaShift = t.hoe_shift_mm;
      break;
    }
  d.retinaImage = reportRetinaImage(scene, options.gazes_deg.front(), retinaShift, options, d.problems);
  if (control.cancelled()) return std::nullopt;
  if (!scene.hoe_layers.empty()) {
    if (auto j = step("selectivity", scene, defaultParameters(*findAnalysis("selectivity")), control, 0.7, 0.75,
                      d.problems, &cancelled))
      d.selectivity = *j;
    if (cancelled) return std::nullopt;
  }

  // Kogelnik vs RCWA (quick grid, scene-independent) (25 %).
  if (options.kogelnik_vs_rcwa) {
    if (auto j = step("kogelnik-vs-rcwa", scene, defaultParameters(*findAnalysis("kogelnik-vs-rcwa")), control, 0.75,
                      1.0, d.problems, &cancelled))
      d.kogelnikVsRcwa = *j;
    if (cancelled) return std::nullopt;
  }
  progress(1.0);

  // Tolerance (the remaining 40 %).
  if (options.tolerance) {
    AnalysisParams tol = defaultParameters(*findAnalysis("tolerance"));
    if (!options.tolerance_spec.isEmpty()) tol["spec"] = options.tolerance_spec;
    tol["trials"] = options.tolerance_trials;
    tol["seed"] = options.tolerance_seed;
    if (auto j = step("tolerance", scene, tol, outer, share, 1.0, d.problems, &cancelled)) d.tolerance = *j;
    if (cancelled) return std::nullopt;
    if (outer.on_progress) outer.on_progress(1.0);
  }
  return d;
}

}  // namespace fovea::studio
