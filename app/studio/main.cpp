// fovea-studio [SCENE] [--screenshot FILE.png [--size WxH]]
//              [--report FILE.pdf|FILE.html [--gaze-deg A[,B]]... [--rays N]]
// Opens the studio on SCENE, or on the embedded prototype bench without one. With
// --screenshot it loads, renders, saves a PNG of the whole main window and exits (0 on
// success, 1 when the scene or the PNG fails, 2 for bad arguments). With --report it writes
// the design report (report_mode.h) and exits.
#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QImage>
#include <QMap>
#include <QTextStream>

#include <cstdio>

#include "app/studio/main_window.h"
#include "app/studio/report_mode.h"
#include "app/studio/window_capture.h"
#include "app/studio/workbench.h"
#include "fovea/version.h"
#include "viz/scene_view.h"
#include "viz/vtk_gl_widget.h"
#include "widgets/message_log.h"

namespace {

void settle(int ms) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < ms) QApplication::processEvents(QEventLoop::AllEvents, 20);
}

}  // namespace

int main(int argc, char** argv) {
  // VTK's OpenGL2 backend needs a 3.2+ core profile, set before the QApplication exists.
  fovea::viz::installDefaultSurfaceFormat();
  QApplication app(argc, argv);
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
  parser.addOption(selectOpt);
  QCommandLineOption reportOpt("report", "Write the design report (.pdf or .html) and exit.", "FILE");
  QCommandLineOption gazeOpt("gaze-deg", "Report: a gaze YAW[,PITCH] (deg) for ray and retina figures; repeatable.",
                             "A[,B]");
  QCommandLineOption raysOpt("rays", "Report: rays per wavelength (default 1500).", "N", "1500");
  parser.addOption(reportOpt);
  parser.addOption(gazeOpt);
  parser.addOption(raysOpt);
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
  if (parser.isSet(viewOpt)) window.sceneView()->showStandardView(views.value(parser.value(viewOpt)));
  if (parser.isSet(selectOpt)) window.selectElement(parser.value(selectOpt));
  if (report) return fovea::studio::runReportMode(window, parser.value(reportOpt), parser.values(gazeOpt), rays);
  if (!screenshot) {
    window.show();
    window.workbench()->startSession();  // preferences, autosave, recovery offer after a crash
    return QApplication::exec();
  }

  window.resize(size);
  window.show();
  settle(400);  // let the window map, lay out the docks and render the 3D view
  const QImage image = window.captureWindow();
  const QString path = parser.value(shotOpt);
  if (image.isNull() || !image.save(path, "PNG")) {
    err << "fovea-studio: could not write the screenshot " << path << "\n";
    return 1;
  }
  QTextStream(stdout) << QFileInfo(path).absoluteFilePath() << "\n";
  return 0;
}
