#pragma once
// What a design report needs computed (any thread, cancellable): a trace at every chosen
// gaze (with its rays, for the retina maps), the gaze sweep (FOV and HOE travel vs gaze, eye
// box), the angular resolution at the first gaze (with its accommodation sweep), the retinal
// image there, the HOE layers' selectivity, the
// Kogelnik-vs-RCWA error/time map and, when requested, the tolerance analysis. Every analysis goes through the studio's
// analysis catalogue (the same numbers as fovea-cli and the analyses panel; cached studies are reused). An analysis
// that fails is recorded in `problems` and left out of the report.
//
// A binocular scene (model/scene/eye_scene.h): the report is of one eye's train, the right
// eye's (the scene's own) unless `eye` is "left"; with both eyes (`eye` empty or "both") it also
// holds each eye's key numbers at the chosen gazes (`eyes`: FOV, efficiency, x_p), the same
// numbers `fovea-cli trace --eye both` gives.

#include <QImage>
#include <QList>
#include <QString>
#include <QStringList>

#include <array>
#include <optional>

#include <nlohmann/json.hpp>

#include "model/analysis/study_runner.h"
#include "model/image/retina_image.h"
#include "model/physics/trace.h"
#include "model/scene/scene.h"
#include "widgets/retina_image_controls.h"

namespace fovea::studio {

struct ReportOptions {
  QList<std::array<double, 2>> gazes_deg;  // yaw, pitch; empty: the scene's gaze
  int rays = 1500;                         // per wavelength, traces and sweep
  double sweep_step_deg = 5.0;
  bool kogelnik_vs_rcwa = true;
  bool follow_gaze = false;  // "HOE follows gaze": trace each gaze with its FOV-maximising HOE shift x_p
  QString title;             // empty: "Design report: <scene name>"
  // Run the tolerance analysis for the report (its Tolerance section); a tolerance result the
  // studio already has for this scene is used without this.
  bool tolerance = false;
  int tolerance_trials = 100;
  QString tolerance_spec;  // empty: the shipped default spec
  int tolerance_seed = 1;
  // A binocular scene's eye: "left", "right" or "both"; empty: both. Ignored for a monocular scene.
  QString eye;
  // The retinal image's speckle and lateral-colour options: the Foveated preview's Retina image
  // options, which the studio passes (model/image/retina_image.h).
  widgets::RetinaPreviewOptions retina;
};

struct GazeTrace {
  std::array<double, 2> gaze_deg{0, 0};
  nlohmann::json json;                       // the trace analysis' result
  TraceResult rays;                          // the same trace with its ray list (ray fans, retina maps)
  std::array<int, 2> grid{0, 0};             // projector ray grid of `rays` (columns, rows) per wavelength
  std::array<double, 2> hoe_shift_mm{0, 0};  // x_p applied (zero unless follow_gaze)
};

// The retinal image of the default test target at the first gaze (issue 29,
// model/image/retina_image.h), sRGB for the page, with its line-of-sight numbers.
struct ReportRetinaImage {
  QImage image;
  // What it was rendered with: gaze, accommodation, HOE shift (x_p at the gaze with
  // follow_gaze, else 0), speckle and calibration.
  image::RetinaImageOptions options;
  std::optional<double> speckle_contrast, speckle_expected;     // speckle on
  std::optional<double> lateral_colour_arcmin;                  // shown at the line of sight, the largest laser's
  double peripheral_spot_arcmin = 0, peripheral_mtf50_cpd = 0;  // 0 when the line of sight misses the HOE
  double foveal_spot_arcmin = 0, foveal_mtf50_cpd = 0;
  double power_in_pupil = 0, power_on_retina = 0;
};

struct ReportData {
  Scene scene;  // the scene the views show: the loaded one, or the left eye's train for eye "left"
  QString scenePath;
  ReportOptions options;
  QList<GazeTrace> traces;
  nlohmann::json sweep, resolution, selectivity, kogelnikVsRcwa;  // null when not computed
  nlohmann::json tolerance;                                       // null unless requested or given
  std::optional<ReportRetinaImage> retinaImage;                   // nothing when it failed
  QStringList problems;
  // A binocular scene: "left" or "right" when the report is of that one eye, else empty; with
  // both eyes `eyes` = {"left": {"gazes": [...]}, "right": {...}}, one entry per chosen gaze
  // {"gaze_deg", "fov_deg": {horizontal, vertical, diagonal}, "mean_efficiency", "x_p_mm",
  // "hoe_shift_mm"} (the trace's exact FOV; x_p the FOV-maximising HOE shift, applied only with
  // follow_gaze). Null otherwise.
  QString eye;
  nlohmann::json eyes;
};

// Parses "10" or "10,-5" (yaw[,pitch] in degrees); false on anything else.
bool parseGaze(const QString& text, std::array<double, 2>* gaze);

std::optional<ReportData> computeReportData(const Scene& scene, const QString& scenePath, ReportOptions options,
                                            const StudyControl& control = {});

}  // namespace fovea::studio
