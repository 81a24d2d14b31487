#include "app/studio/report_mode.h"

#include <QApplication>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include "app/studio/main_window.h"
#include "app/studio/report_data.h"
#include "app/studio/workbench.h"
#include "widgets/message_log.h"

namespace fovea::studio {

int runReportMode(MainWindow& window, const QString& out, const QStringList& gazes, int rays) {
  QTextStream err(stderr);
  const QString ext = QFileInfo(out).suffix().toLower();
  if (ext != "pdf" && ext != "html" && ext != "htm") {
    err << "fovea-studio: --report: the file must end in .pdf or .html, got \"" << out << "\"\n";
    return 2;
  }
  ReportOptions options;
  options.rays = rays;
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
  if (!window.workbench()->exportReport(out, options, &error, &pages, &figures)) {
    err << "fovea-studio: the report was not written: " << error << "\n";
    return 1;
  }
  QJsonArray problems;
  for (const QString& e : window.messageLog()->entries())
    if (e.startsWith("warning: report: ")) problems << e.mid(17);
  const QJsonObject manifest{{"out", QFileInfo(out).absoluteFilePath()},
                             {"format", ext == "htm" ? QString("html") : ext},
                             {"pages", ext == "pdf" ? QJsonValue(pages) : QJsonValue()},
                             {"figures", figures},
                             {"problems", problems}};
  QTextStream(stdout) << QJsonDocument(manifest).toJson(QJsonDocument::Indented);
  return 0;
}

}  // namespace fovea::studio
