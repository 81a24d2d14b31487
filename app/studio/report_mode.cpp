#include "app/studio/report_mode.h"

#include <QApplication>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include <algorithm>

#include "app/studio/analysis_features.h"
#include "app/studio/main_window.h"
#include "app/studio/report_data.h"
#include "widgets/message_log.h"
#include "widgets/preview_panel.h"
#include "widgets/scene_document.h"

namespace fovea::studio {

int runReportMode(MainWindow& window, const QString& out, const QStringList& gazes, int rays, int toleranceTrials,
                  const QString& toleranceSpec, const QString& eye, const QString& retina) {
  QTextStream err(stderr);
  const QString ext = QFileInfo(out).suffix().toLower();
  if (ext != "pdf" && ext != "html" && ext != "htm") {
    err << "fovea-studio: --report: the file must end in .pdf or .html, got \"" << out << "\"\n";
    return 2;
  }
  if (!eye.isEmpty() && eye != "left" && eye != "right" && eye != "both") {
    err << "fovea-studio: --report-eye: expected left, right or both, got \"" << eye << "\"\n";
    return 2;
  }
  if (!eye.isEmpty() && !window.document()->scene().binocular) {
    err << "fovea-studio: --report-eye " << eye << ": the scene is monocular (no \"binocular\" block)\n";
    return 2;
  }
  // The retinal image's options go where the report reads them: the Foveated preview's controls.
  if (!retina.isEmpty()) {
    const QStringList parts = retina.split(',');
    bool ok = parts.size() == 3 || parts.size() == 4;
    const int speckle = ok ? parts[0].toInt(&ok) : 0;
    bool seed_ok = true;
    const int seed = parts.size() == 4 ? parts[3].toInt(&seed_ok) : 1;
    ok = ok && seed_ok && speckle >= 0 && speckle <= 16 && (parts[1] == "pixel" || parts[1] == "pupil") &&
         (parts[2] == "one" || parts[2] == "per-laser") && seed >= 1 &&
         seed <= widgets::RetinaImageControls::kMaxSpeckleSeed;
    if (!ok) {
      err << "fovea-studio: --report-retina: expected SPECKLE,GRAIN,CALIBRATION[,SEED] (0..16, pixel|pupil, "
             "one|per-laser, 1.."
          << widgets::RetinaImageControls::kMaxSpeckleSeed << "), got \"" << retina << "\"\n";
      return 2;
    }
    if (widgets::PreviewPanel* preview = window.previewPanel())
      preview->setRetinaOptions({speckle, parts[1] == "pupil", parts[2] == "per-laser", seed});
  }
  ReportOptions options;
  options.eye = eye;
  options.rays = rays;
  options.tolerance = toleranceTrials > 0;
  options.tolerance_trials = std::max(1, toleranceTrials);
  options.tolerance_spec = toleranceSpec;
  for (const QString& text : gazes) {
    std::array<double, 2> g{};
    if (!parseGaze(text, &g)) {
      err << "fovea-studio: --gaze-deg: expected YAW[,PITCH] in degrees (|angle| <= 90), got \"" << text << "\"\n";
      return 2;
    }
    options.gazes_deg << g;
  }
  // Headless: the 3-D figures get the whole window (the docks would only shrink the view).
  for (QDockWidget* dock : window.findChildren<QDockWidget*>()) dock->hide();
  window.resize(1500, 1000);
  window.show();
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < 400) QApplication::processEvents(QEventLoop::AllEvents, 20);  // map, lay out, first render

  QString error;
  int pages = 0, figures = 0;
  QList<GazeFigureStats> gazeFigures;
  QStringList sections;
  nlohmann::json eyes;
  if (!window.analysisFeatures()->exportReport(out, options, &error, &pages, &figures, &gazeFigures, &sections,
                                               &eyes)) {
    err << "fovea-studio: the report was not written: " << error << "\n";
    return 1;
  }
  QJsonArray problems;
  for (const QString& e : window.messageLog()->entries())
    if (e.startsWith("warning: report: ")) problems << e.mid(17);
  QJsonArray gazeJson;  // what each "bench at the gaze" figure drew
  for (const GazeFigureStats& s : gazeFigures)
    gazeJson << QJsonObject{{"figure", s.figureId},
                            {"gaze_deg", QJsonArray{s.gaze_deg[0], s.gaze_deg[1]}},
                            {"hoe_shift_mm", QJsonArray{s.hoe_shift_mm[0], s.hoe_shift_mm[1]}},
                            {"rays_drawn", s.overlay.rays_drawn},
                            {"rays_in_pupil", s.overlay.rays_in_pupil},
                            {"rays_missing", s.overlay.rays_missing},
                            {"rays_low", s.overlay.rays_low},
                            {"overlay_pixels", s.overlay_pixels},
                            {"retina_cells", s.retina_cells}};
  QJsonObject manifest{{"out", QFileInfo(out).absoluteFilePath()},
                       {"format", ext == "htm" ? QString("html") : ext},
                       {"pages", ext == "pdf" ? QJsonValue(pages) : QJsonValue()},
                       {"figures", figures},
                       {"problems", problems},
                       {"gaze_figures", gazeJson},
                       {"sections", QJsonArray::fromStringList(sections)}};
  if (const widgets::PreviewPanel* preview = window.previewPanel()) {  // the options the report used
    const widgets::RetinaPreviewOptions r = preview->retinaOptions();
    manifest.insert("retina_image", QJsonObject{{"speckle_patterns", r.speckle_patterns},
                                                {"speckle_grain", r.speckle_grain_pupil ? "pupil" : "pixel"},
                                                {"calibration", r.per_laser_calibration ? "per-laser" : "one"},
                                                {"speckle_seed", r.speckle_seed}});
  }
  if (eyes.is_object())  // "eye" or "eyes" (report_data.h)
    for (auto it = eyes.begin(); it != eyes.end(); ++it)
      manifest.insert(
          QString::fromStdString(it.key()),
          QJsonDocument::fromJson(QByteArray::fromStdString(nlohmann::json::array({it.value()}).dump())).array().at(0));
  QTextStream(stdout) << QJsonDocument(manifest).toJson(QJsonDocument::Indented);
  return 0;
}

}  // namespace fovea::studio
