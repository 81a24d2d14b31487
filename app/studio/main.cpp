// fovea-studio [SCENE] [--screenshot FILE.png [--size WxH] [--grab window|view|retina|kcloud]]
//              [--view iso|top|side|eye] [--zoom F] [--select ID] [--gaze-deg YAW[,PITCH]]
//              [--follow-gaze] [--show rays,effmap,kcloud,retina] [--rays N]
//              [--report FILE.pdf|FILE.html [--gaze-deg A[,B]]... [--rays N]]
// Opens the studio on SCENE, or on the embedded prototype bench without one. With
// --screenshot it loads, waits for the live trace, renders, saves a PNG of the whole main
// window (or of one view with --grab) and exits (0 on success, 1 when the scene, the trace
// or the PNG fails, 2 for bad arguments). With --report it writes the design report
// (report_mode.h) and exits.
#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QImage>
#include <QMap>
#include <QTextStream>

#include <cmath>
#include <cstdio>

#include "app/studio/analysis_features.h"
#include "app/studio/live_trace_features.h"
#include "app/studio/main_window.h"
#include "app/studio/report_mode.h"
#include "app/studio/window_capture.h"
#include "fovea/version.h"
#include "model/memory_policy.h"
#include "model/vector_state.h"
#include "viz/kspace_view.h"
#include "viz/scene_view.h"
#include "viz/software_gl.h"
#include "viz/vtk_gl_widget.h"
#include "widgets/bench/devices_panel.h"
#include "widgets/display_panel.h"
#include "widgets/gaze_panel.h"
#include "widgets/message_log.h"
#include "widgets/preview_panel.h"
#include "widgets/retina_view.h"

namespace {

void settle(int ms) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < ms) QApplication::processEvents(QEventLoop::AllEvents, 20);
}

}  // namespace

int main(int argc, char** argv) {
  fovea::keepFreedMemoryForReuse();                 // large buffers reused between renders (model/memory_policy.h)
  fovea::viz::matchSoftwareRasterizerToAffinity();  // before any OpenGL context
  // VTK's OpenGL2 backend needs a 3.2+ core profile, set before the QApplication exists.
  fovea::viz::installDefaultSurfaceFormat();
  QApplication app(argc, argv);
  // Qt leaves the GUI thread's upper AVX state dirty; threads started from it inherit it
  // (model/vector_state.h).
  fovea::clearUpperVectorState();
  fovea::clearUpperVectorStateOnTbbThreads();
  QApplication::setOrganizationName("FoveatedARStudio");
  QApplication::setApplicationName("fovea-studio");
  QApplication::setApplicationVersion(FOVEA_VERSION_STRING);

  QCommandLineParser parser;
  parser.setApplicationDescription("Foveated AR Studio: design, simulate and bench-test a foveated AR display.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("SCENE", "Scene file to open (default: the embedded prototype bench).", "[SCENE]");
  QCommandLineOption shotOpt("screenshot", "Load, render, save a PNG of the main window to FILE and exit.", "FILE");
  QCommandLineOption sizeOpt("size", "Window size for --screenshot (default 1600x1000).", "WxH", "1600x1000");
  QCommandLineOption viewOpt("view", "Camera: iso, top, side or eye.", "NAME", "iso");
  QCommandLineOption selectOpt("select", "Select an element, e.g. eye, hoe_layers[1].", "ID");
  parser.addOption(shotOpt);
  parser.addOption(sizeOpt);
  parser.addOption(viewOpt);
  QCommandLineOption followOpt("follow-gaze", "HOE follows gaze: apply the travel x_p(alpha) that maximises the FOV.");
  QCommandLineOption showOpt(
      "show",
      "Views to show, comma-separated: rays (ray fans), effmap (efficiency map on the HOE), "
      "kcloud (grating-vector cloud dock), retina (retina dock), retina-image (the Foveated preview "
      "dock in its Retina image mode), bench (devices dock), none. "
      "Default: rays,retina.",
      "LIST");
  QCommandLineOption zoomOpt("zoom", "Camera zoom factor applied after --view (0.2..20, e.g. 1.8).", "F");
  QCommandLineOption grabOpt("grab", "What --screenshot saves: window (default), view (3D view), retina, kcloud.",
                             "WHAT", "window");
  parser.addOption(selectOpt);
  QCommandLineOption reportOpt("report", "Write the design report (.pdf or .html) and exit.", "FILE");
  QCommandLineOption gazeOpt("gaze-deg",
                             "Gaze YAW[,PITCH] in degrees: the eye's gaze in the studio and screenshots; for "
                             "--report a gaze for ray and retina figures (repeatable).",
                             "A[,B]");
  QCommandLineOption raysOpt("rays",
                             "Rays per wavelength: the live trace (200..40000, default 4000) or the report "
                             "(default 1500).",
                             "N", "1500");
  QCommandLineOption reportToleranceOpt(
      "report-tolerance", "With --report: add the Tolerance section from N trials (default 0: none).", "N", "0");
  QCommandLineOption reportToleranceSpecOpt(
      "report-tolerance-spec", "With --report-tolerance: the tolerance spec (default: the shipped one).", "FILE");
  QCommandLineOption reportEyeOpt(
      "report-eye", "With --report on a binocular scene: the eye the report is of, left, right or both (default).",
      "EYE");
  QCommandLineOption reportRetinaOpt(
      "report-retina",
      "With --report: the retinal image's speckle patterns (0..16), grain (pixel|pupil), calibration "
      "(one|per-laser) and optional speckle seed (1..999, default 1).",
      "SPECKLE,GRAIN,CALIBRATION[,SEED]");
  parser.addOption(reportOpt);
  parser.addOption(reportEyeOpt);
  parser.addOption(reportRetinaOpt);
  parser.addOption(reportToleranceOpt);
  parser.addOption(reportToleranceSpecOpt);
  parser.addOption(gazeOpt);
  parser.addOption(raysOpt);
  parser.addOption(followOpt);
  parser.addOption(showOpt);
  parser.addOption(grabOpt);
  parser.addOption(zoomOpt);
  parser.process(app);

  QTextStream err(stderr);
  const QStringList args = parser.positionalArguments();
  if (args.size() > 1) {
    err << "fovea-studio: at most one SCENE, got " << args.size() << "\n";
    return 2;
  }
  QSize size;
  if (!fovea::studio::parseWindowSize(parser.value(sizeOpt), &size)) {
    err << "fovea-studio: --size: expected WxH such as 1600x1000 (64..8192 each), got \"" << parser.value(sizeOpt)
        << "\"\n";
    return 2;
  }
  const bool report = parser.isSet(reportOpt);
  const bool screenshot = parser.isSet(shotOpt) || report;
  bool raysOk = false;
  const int rays = parser.value(raysOpt).toInt(&raysOk);
  if (!raysOk || rays < 50 || rays > 1000000) {
    err << "fovea-studio: --rays: expected a whole number in 50 .. 1000000, got \"" << parser.value(raysOpt) << "\"\n";
    return 2;
  }
  const QMap<QString, fovea::viz::StandardView> views{{"iso", fovea::viz::StandardView::Isometric},
                                                      {"top", fovea::viz::StandardView::Top},
                                                      {"side", fovea::viz::StandardView::Side},
                                                      {"eye", fovea::viz::StandardView::EyeView}};
  if (!views.contains(parser.value(viewOpt))) {
    err << "fovea-studio: --view: expected iso, top, side or eye, got \"" << parser.value(viewOpt) << "\"\n";
    return 2;
  }

  double gazeYaw = 0, gazePitch = 0;
  if (parser.isSet(gazeOpt) && !report) {
    const QStringList parts = parser.value(gazeOpt).split(',');
    bool ok1 = parts.size() <= 2, ok2 = true;
    if (ok1) gazeYaw = parts.value(0).toDouble(&ok1);
    if (ok1 && parts.size() == 2) gazePitch = parts[1].toDouble(&ok2);
    if (!ok1 || !ok2 || std::abs(gazeYaw) > 40 || std::abs(gazePitch) > 40) {
      err << "fovea-studio: --gaze-deg: expected YAW or YAW,PITCH in degrees within +-40, got \""
          << parser.value(gazeOpt) << "\"\n";
      return 2;
    }
  }
  if (parser.isSet(raysOpt) && !report && (rays < 200 || rays > 40000)) {
    err << "fovea-studio: --rays: the live trace takes 200..40000 rays, got " << rays << "\n";
    return 2;
  }
  double zoom = 1.0;
  if (parser.isSet(zoomOpt)) {
    bool ok = false;
    zoom = parser.value(zoomOpt).toDouble(&ok);
    if (!ok || !(zoom >= 0.2 && zoom <= 20.0)) {
      err << "fovea-studio: --zoom: expected a factor 0.2..20, got \"" << parser.value(zoomOpt) << "\"\n";
      return 2;
    }
  }
  const QString grab = parser.value(grabOpt);
  if (!QStringList{"window", "view", "retina", "kcloud"}.contains(grab)) {
    err << "fovea-studio: --grab: expected window, view, retina or kcloud, got \"" << grab << "\"\n";
    return 2;
  }

  if (report) fovea::studio::MainWindow::setBenchAutoStart(false);  // the report needs no live bench
  fovea::studio::MainWindow window;
  window.setPersistentSettings(!screenshot);
  window.restoreSettings();
  if (!args.isEmpty() && !window.openFile(args.front(), !screenshot)) {
    if (screenshot) {
      for (const QString& e : window.messageLog()->entries())
        if (e.startsWith("error: ")) err << e.mid(7) << "\n";
      return 1;
    }
  }
  fovea::studio::LiveTraceFeatures* bench = window.liveTraceFeatures();
  if (parser.isSet(gazeOpt) && !report) bench->setStartGaze(gazeYaw, gazePitch);
  if (parser.isSet(followOpt)) bench->gazePanel()->setFollowGaze(true);
  if (parser.isSet(raysOpt)) bench->displayPanel()->setTraceRays(rays);
  if (parser.isSet(showOpt)) {
    QString why;
    if (!bench->applyShowList(parser.value(showOpt).split(','), &why)) {
      err << "fovea-studio: --show: " << why << "\n";
      return 2;
    }
  }
  if (parser.isSet(viewOpt)) window.sceneView()->showStandardView(views.value(parser.value(viewOpt)));
  if (parser.isSet(zoomOpt)) window.sceneView()->zoomCamera(zoom);
  if (parser.isSet(selectOpt)) window.selectElement(parser.value(selectOpt));
  if (report) {
    bool trialsOk = false;
    const int trials = parser.value(reportToleranceOpt).toInt(&trialsOk);
    if (!trialsOk || trials < 0 || trials > 1000000) {
      err << "fovea-studio: --report-tolerance: expected a whole number in 0 .. 1000000, got \""
          << parser.value(reportToleranceOpt) << "\"\n";
      return 2;
    }
    return fovea::studio::runReportMode(window, parser.value(reportOpt), parser.values(gazeOpt), rays, trials,
                                        parser.value(reportToleranceSpecOpt), parser.value(reportEyeOpt),
                                        parser.value(reportRetinaOpt));
  }
  if (!screenshot) {
    window.show();
    window.analysisFeatures()->startSession();  // preferences, autosave, recovery offer after a crash
    return QApplication::exec();
  }

  window.resize(size);
  window.show();
  settle(400);  // let the window map, lay out the docks and render the 3D view
  if (!bench->waitForTrace()) {
    err << "fovea-studio: the live trace did not finish\n";
    return 1;
  }
  settle(200);
  // The bench dock shown: wait (up to 10 s) for the bench and its first camera frame.
  if (fovea::widgets::DevicesPanel* devices = window.devicesPanel(); devices && devices->isVisible()) {
    QElapsedTimer t;
    t.start();
    while (t.elapsed() < 10000 && !(devices->isConnected() && devices->hasCameraFrame())) settle(50);
    settle(300);
  }
  // The preview in its Retina image mode: wait (up to 60 s) for its first retinal image.
  if (fovea::widgets::PreviewPanel* preview = window.previewPanel();
      preview && preview->isVisible() && preview->mode() == fovea::widgets::PreviewPanel::Mode::RetinaImage) {
    QElapsedTimer t;
    t.start();
    while (t.elapsed() < 60000 && (!preview->lastFrame().accommodation_d || preview->lastFrame().retina.isNull()))
      settle(50);
    settle(200);
  }
  QImage image;
  if (grab == "view")  // opaque, as on screen (the labels' boxes keep their darkness)
    image = fovea::studio::opaqueFramebuffer(window.sceneView()->renderToImage());
  else if (grab == "retina")
    image = bench->retinaView()->render(size);
  else if (grab == "kcloud")
    image = fovea::studio::opaqueFramebuffer(bench->kspaceView()->renderToImage());
  else
    image = window.captureWindow();
  const QString path = parser.value(shotOpt);
  if (image.isNull() || !image.save(path, "PNG")) {
    err << "fovea-studio: could not write the screenshot " << path << "\n";
    return 1;
  }
  QTextStream(stdout) << QFileInfo(path).absoluteFilePath() << "\n";
  return 0;
}
