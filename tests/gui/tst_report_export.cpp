// File ▸ Export Report… driven as a user would: the action opens the options dialog (one
// gaze, few rays), then the save dialog (a path in the test's scratch folder); while the
// report is computed and written a progress dialog shows the steps, and the status bar and
// the message log end with "Report saved to <path>" naming the file that is there.
// Cancelling in the progress dialog between two steps writes nothing: no report, and no
// half-written temporary file beside it.

#include <QtTest>

#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QLineEdit>
#include <QProgressDialog>
#include <QPushButton>
#include <QRegularExpression>
#include <QSpinBox>
#include <QStatusBar>

#include <functional>

#include "app/studio/main_window.h"
#include "tests/test_files.h"
#include "viz/vtk_gl_widget.h"
#include "widgets/message_log.h"
#include "widgets/preferences.h"

namespace tst_report_export {

using namespace fovea;

namespace {

// What the user saw while the report was made.
struct Watched {
  QStringList status;          // every status-bar message, in order
  QStringList progressLabels;  // the progress dialog's labels, in order
  bool progressShown = false;  // the dialog was on screen
  int progressMax = -1;        // its maximum, when it was shown
  bool optionsAnswered = false, fileAnswered = false;
};

// Answers the dialogs of File ▸ Export Report… as they come up (polled every 20 ms, also
// from the nested event loops the export runs): the options dialog with `gazes` and `rays`,
// the save dialog with `path`.
class DialogAnswerer : public QObject {
 public:
  DialogAnswerer(QString path, Watched* watched) : path_(std::move(path)), watched_(watched) {
    connect(&timer_, &QTimer::timeout, this, &DialogAnswerer::poll);
    timer_.start(20);
  }

 private:
  void poll() {
    QWidget* modal = QApplication::activeModalWidget();
    if (auto* files = qobject_cast<QFileDialog*>(modal)) {
      watched_->fileAnswered = true;
      files->selectFile(path_);
      static_cast<QDialog*>(files)->accept();  // QFileDialog::accept, public through QDialog
    } else if (auto* dialog = qobject_cast<QDialog*>(modal);
               dialog && dialog->windowTitle() == "Export Report" && !qobject_cast<QProgressDialog*>(modal)) {
      watched_->optionsAnswered = true;
      dialog->findChild<QLineEdit*>({}, Qt::FindDirectChildrenOnly)->setText("0,0");  // one gaze: the scene's own
      for (QSpinBox* box : dialog->findChildren<QSpinBox*>())
        if (box->objectName() != "reportToleranceTrials") box->setValue(100);  // rays per wavelength
      dialog->findChild<QDialogButtonBox*>()->button(QDialogButtonBox::Ok)->click();
    }
  }

  QString path_;
  Watched* watched_;
  QTimer timer_;
};

// Files in `dir` (a report's folder) other than `except`.
QStringList othersIn(const QString& dir, const QString& except) {
  QStringList out = QDir(dir).entryList(QDir::Files | QDir::Hidden);
  out.removeAll(except);
  return out;
}

}  // namespace

class TestReportExport : public QObject {
  Q_OBJECT
 private:
  std::unique_ptr<studio::MainWindow> w;
  Watched seen;

  // Triggers File ▸ Export Report… for `path`. `atStep(dialog)` runs at each step of the
  // progress dialog, once its label shows the step (the status line comes just before the
  // label; the export processes events before it checks Cancel).
  void exportThroughTheMenu(const QString& path, const std::function<void(QProgressDialog*)>& atStep = {}) {
    seen = {};
    QAction* action = w->findChild<QAction*>("exportReport");
    QVERIFY(action);
    const auto watch = connect(w->statusBar(), &QStatusBar::messageChanged, this, [this, atStep](const QString& m) {
      if (!m.contains("report", Qt::CaseInsensitive)) return;  // not the live trace's, not a timeout's ""
      seen.status << m;
      QTimer::singleShot(0, this, [this, atStep] {
        auto* progress = w->findChild<QProgressDialog*>("reportProgress");
        if (!progress) return;
        if (progress->isVisible()) {
          seen.progressShown = true;
          seen.progressMax = progress->maximum();
        }
        if (seen.progressLabels.value(seen.progressLabels.size() - 1) != progress->labelText())
          seen.progressLabels << progress->labelText();
        if (atStep) atStep(progress);
      });
    });
    DialogAnswerer answerer(path, &seen);
    action->trigger();  // returns when the export has finished (or was cancelled)
    disconnect(watch);
    QVERIFY(seen.optionsAnswered && seen.fileAnswered);
  }

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    studio::MainWindow::setBenchAutoStart(false);
    widgets::Preferences::instance().setValues(widgets::PreferenceValues{});
  }

  void init() {
    w = std::make_unique<studio::MainWindow>();
    w->resize(1400, 900);
    w->show();
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    w->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w.get()));  // the export shows its progress to an active window
  }
  void cleanup() { w.reset(); }

  void savedReportIsNamedAndProgressShown() {
    const QString dir = QString::fromStdString(testing::testTmpDir("gui_report_export/saved", true).string());
    const QString path = dir + "/prototype-report.pdf";
    exportThroughTheMenu(path);
    // The file is there, a PDF.
    QFile file(path);
    QVERIFY2(file.open(QIODevice::ReadOnly), qPrintable(path));
    QVERIFY(file.size() > 10000);
    QCOMPARE(file.read(5), QByteArray("%PDF-"));
    QCOMPARE(othersIn(dir, "prototype-report.pdf"), QStringList());
    // The steps, in the status bar and in the progress dialog.
    const QString writing = "Writing the report " + path + "… (";
    QCOMPARE(seen.status,
             QStringList({writing + "computing its analyses)", writing + "composing the figures)",
                          writing + "writing prototype-report.pdf)", writing + "done)", "Report saved to " + path}));
    QVERIFY(seen.progressShown);
    QCOMPARE(seen.progressMax, 1200);
    QCOMPARE(seen.progressLabels, QStringList({"Computing the report's analyses…", "composing the figures",
                                               "writing prototype-report.pdf", "done"}));
    // The dialog is gone and the message log ends with the same words.
    QVERIFY(!w->findChild<QProgressDialog*>("reportProgress"));
    QCOMPARE(w->statusBar()->currentMessage(), "Report saved to " + path);
    const QString last = w->messageLog()->entries().last();
    static const QRegularExpression saved("^info: Report saved to (.+) \\((\\d+) figure");
    const auto m = saved.match(last);
    QVERIFY2(m.hasMatch(), qPrintable(last));
    QCOMPARE(m.captured(1), path);
    QVERIFY2(m.captured(2).toInt() >= 10, qPrintable(last));  // the standard views, the gaze's, the plots
  }

  void cancelBetweenStepsWritesNothing_data() {
    QTest::addColumn<QString>("step");
    QTest::newRow("before the figures") << "composing the figures";
    QTest::newRow("before writing") << "writing prototype-report.pdf";
  }
  void cancelBetweenStepsWritesNothing() {
    QFETCH(QString, step);
    const QString dir = QString::fromStdString(testing::testTmpDir("gui_report_export/cancelled", true).string());
    const QString path = dir + "/prototype-report.pdf";
    bool cancelled = false, shown = false;
    exportThroughTheMenu(path, [&](QProgressDialog* progress) {
      if (cancelled || progress->labelText() != step) return;
      // Cancel as the user would, while the dialog shows this step.
      shown = progress->isVisible();
      progress->findChild<QPushButton*>()->click();
      cancelled = true;
    });
    QVERIFY2(cancelled, qPrintable(seen.progressLabels.join(" | ")));
    QVERIFY(shown);  // the user saw the step they cancelled at
    QVERIFY2(!QFileInfo::exists(path), qPrintable(path));
    QCOMPARE(othersIn(dir, {}), QStringList());  // no temporary file either
    QCOMPARE(w->statusBar()->currentMessage(), QString("Report not written: cancelled"));
    QCOMPARE(w->messageLog()->entries().last(), QString("error: Report not written: cancelled"));
    QVERIFY(!seen.status.join('\n').contains("Report saved"));
    QVERIFY(!w->findChild<QProgressDialog*>("reportProgress"));
  }
};

int main(int argc, char** argv) {
  viz::installDefaultSurfaceFormat();  // before the QApplication, as fovea-studio does
  const auto config = testing::testTmpDir("gui_report_export/config", true);
  qputenv("XDG_CONFIG_HOME", QByteArray::fromStdString(config.string()));
  QApplication app(argc, argv);
  QApplication::setOrganizationName("FoveatedARStudioTest");
  QApplication::setApplicationName("tst_report_export");
  TestReportExport test;
  return QTest::qExec(&test, argc, argv);
}

}  // namespace tst_report_export
#include "tst_report_export.moc"
