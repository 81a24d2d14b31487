// Never lose work: autosave writes a recovery file within the interval after an edit and
// removes it when the scene is saved or undone to clean; files left by a studio that died
// (no lock, or a lock whose process is gone) are offered on the next start and can be
// recovered (the changes as one undoable, unsaved step on top of the saved file) or
// declined (files removed, scene unchanged); a live session's files are never offered.
// Preferences persist through QSettings.
#include <QtTest>

#include <QAbstractButton>
#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLockFile>
#include <QMessageBox>
#include <QProcess>
#include <QSettings>
#include <QSysInfo>
#include <QUndoStack>

#include "app/studio/analysis_features.h"
#include "app/studio/main_window.h"
#include "model/scene/scene_io.h"
#include "tests/gui/analysis_panel_fixture.h"
#include "widgets/autosave.h"
#include "widgets/preferences.h"
#include "widgets/scene_document.h"

namespace tst_recovery {

using namespace fovea;
using namespace fovea::widgets;
using fovea::embeddedDefaultScene;
using fovea::testing::testTmpPath;

namespace {

QString freshDir(const std::string& name) {
  return testTmpPath("gui_recovery/" + name, true);
}

// What a crashed studio leaves: the scene, its meta, and a lock naming a process that is gone.
void writeCrashLeftovers(const QString& dir, const Scene& scene, const QString& originalPath, bool withDeadLock) {
  const QString base = dir + "/session-424242-1";
  QFile s(base + ".json");
  QVERIFY(s.open(QIODevice::WriteOnly));
  s.write(QByteArray::fromStdString(serializeScene(scene)));
  s.close();
  QFile m(base + ".meta.json");
  QVERIFY(m.open(QIODevice::WriteOnly));
  m.write(QJsonDocument(QJsonObject{{"original_path", originalPath},
                                    {"display_name", "bench.json"},
                                    {"saved_at", "2026-01-02T03:04:05.000Z"}})
              .toJson());
  m.close();
  if (withDeadLock) {
    QProcess p;  // a process that has exited: its pid is free
    p.start("true");
    QVERIFY(p.waitForFinished());
    const qint64 pid = p.processId() > 0 ? p.processId() : 999999;
    QFile l(base + ".lock");
    QVERIFY(l.open(QIODevice::WriteOnly));
    l.write(QByteArray::number(pid) + "\nfovea-studio\n" + QSysInfo::machineHostName().toUtf8() + "\n" +
            QSysInfo::machineUniqueId() + "\n" + QSysInfo::bootUniqueId() + "\n");
  }
}

// Clicks the button named `name` of the recovery message box once it is shown.
void answerRecoveryWith(const QString& name) {
  QTimer::singleShot(200, [name] {
    auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
    if (!box) return;
    for (QAbstractButton* b : box->buttons())
      if (b->objectName() == name) b->click();
  });
}

}  // namespace

class TestRecovery : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() {
    QCoreApplication::setOrganizationName("FoveatedARStudioTest");
    QCoreApplication::setApplicationName("tst_recovery");
    QSettings().clear();
  }

  void autosaveFollowsUnsavedChanges() {
    const QString dir = freshDir("autosave");
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    Autosaver saver(&doc, dir);
    saver.setIntervalSeconds(1);
    QVERIFY(!saver.hasRecoveryFile());
    QVERIFY(doc.applyEdit("relief", [](Scene& s) { s.eye.relief_mm = 24.5; }).isEmpty());
    QTRY_VERIFY_WITH_TIMEOUT(saver.hasRecoveryFile(), 3000);
    const SceneLoadResult r = loadSceneFile(saver.recoveryFile().toStdString());
    QVERIFY(r.ok());
    QCOMPARE(r.scene->eye.relief_mm, 24.5);
    // Our own live session is never an orphan.
    QVERIFY(Autosaver::findOrphans(dir).isEmpty());
    // Undo back to the saved state removes the file.
    doc.undoStack()->undo();
    QVERIFY(!doc.isModified());
    QVERIFY(!saver.hasRecoveryFile());
    // A save (clean state) removes it too.
    QVERIFY(doc.applyEdit("relief", [](Scene& s) { s.eye.relief_mm = 23.0; }).isEmpty());
    QVERIFY(saver.saveNow());
    QVERIFY(saver.hasRecoveryFile());
    doc.markSaved(dir + "/bench.json");
    QVERIFY(!saver.hasRecoveryFile());
  }

  void cleanExitRemovesTheFiles() {
    const QString dir = freshDir("clean-exit");
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    {
      Autosaver saver(&doc, dir);
      QVERIFY(doc.applyEdit("pupil", [](Scene& s) { s.eye.pupil_diameter_mm = 4.0; }).isEmpty());
      QVERIFY(saver.saveNow());
      QVERIFY(saver.hasRecoveryFile());
    }
    QVERIFY(QDir(dir).entryList({"session-*.json"}, QDir::Files).isEmpty());
  }

  void crashLeftoversAreFound() {
    const QString dir = freshDir("orphans");
    writeCrashLeftovers(dir, embeddedDefaultScene(), {}, true);
    const QList<RecoveryEntry> found = Autosaver::findOrphans(dir);
    QCOMPARE(found.size(), 1);
    QCOMPARE(found[0].displayName, QString("bench.json"));
    QVERIFY(found[0].savedAt.isValid());
    // A lock held by a running studio (here: this process) hides its files.
    QLockFile live(dir + "/session-424242-1.lock");
    QVERIFY(live.tryLock(0));
    QVERIFY(Autosaver::findOrphans(dir).isEmpty());
    live.unlock();
    QCOMPARE(Autosaver::findOrphans(dir).size(), 1);
  }

  void recoverOnStartRestoresTheChanges() {
    const QString dir = freshDir("recover");
    // The saved file, and the crashed session's unsaved version of it.
    const QString saved = dir + "/bench.json";
    saveSceneFileAtomic(embeddedDefaultScene(), saved.toStdString());
    Scene changed = embeddedDefaultScene();
    changed.eye.relief_mm = 27.0;
    changed.hoe_layers[1].n1 = 0.021;
    writeCrashLeftovers(dir, changed, saved, true);

    studio::MainWindow window;
    answerRecoveryWith("recover");
    window.analysisFeatures()->startSession(dir);
    const Scene& now = window.document()->scene();
    QCOMPARE(now.eye.relief_mm, 27.0);
    QCOMPARE(now.hoe_layers[1].n1, 0.021);
    QVERIFY(window.document()->isModified());
    QCOMPARE(window.document()->filePath(), QFileInfo(saved).absoluteFilePath());
    // The crashed session's files are gone; this session autosaved the recovered scene.
    QVERIFY(!QFile::exists(dir + "/session-424242-1.json"));
    QVERIFY(window.analysisFeatures()->autosaver()->hasRecoveryFile());
    // Undo goes back to the file on disk.
    window.document()->undoStack()->undo();
    QCOMPARE(window.document()->scene().eye.relief_mm, embeddedDefaultScene().eye.relief_mm);
    window.document()->undoStack()->redo();
    QCOMPARE(window.document()->scene().eye.relief_mm, 27.0);
  }

  void declineDiscardsTheLeftovers() {
    const QString dir = freshDir("decline");
    Scene changed = embeddedDefaultScene();
    changed.eye.relief_mm = 30.0;
    writeCrashLeftovers(dir, changed, {}, false);  // killed before it ever took a lock
    studio::MainWindow window;
    const double before = window.document()->scene().eye.relief_mm;
    answerRecoveryWith("discard");
    window.analysisFeatures()->startSession(dir);
    QCOMPARE(window.document()->scene().eye.relief_mm, before);
    QVERIFY(!window.document()->isModified());
    QVERIFY(!QFile::exists(dir + "/session-424242-1.json"));
    QVERIFY(!QFile::exists(dir + "/session-424242-1.meta.json"));
  }

  void laterKeepsTheLeftovers() {
    const QString dir = freshDir("later");
    writeCrashLeftovers(dir, embeddedDefaultScene(), {}, true);
    studio::MainWindow window;
    answerRecoveryWith("later");
    window.analysisFeatures()->startSession(dir);
    QVERIFY(QFile::exists(dir + "/session-424242-1.json"));
    QCOMPARE(Autosaver::findOrphans(dir).size(), 1);
  }

  void preferencesPersist() {
    PreferenceValues v;
    v.length = LengthUnit::Micrometre;
    v.angle = AngleUnit::Radian;
    v.defaultRays = 2500;
    v.theme = Theme::Dark;
    v.autosaveSeconds = 12;
    v.dragResolutionPercent = 75;
    Preferences::instance().setPersistent(true);
    QSignalSpy changed(&Preferences::instance(), &Preferences::changed);
    Preferences::instance().setValues(v);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(QSettings().value("preferences/lengthUnit").toString(), QString("um"));
    Preferences::instance().setValues(PreferenceValues{});  // in memory only differs now
    QSettings().setValue("preferences/lengthUnit", "um");
    QSettings().setValue("preferences/angleUnit", "rad");
    QSettings().setValue("preferences/defaultRays", 2500);
    QSettings().setValue("preferences/theme", "dark");
    QSettings().setValue("preferences/autosaveSeconds", 12);
    QSettings().setValue("preferences/dragResolutionPercent", 75);
    Preferences::instance().load();
    QCOMPARE(Preferences::instance().values(), v);
    QCOMPARE(Preferences::instance().units().length(2.5), QString("2500 µm"));
    QVERIFY(QApplication::palette().color(QPalette::Window).lightness() < 110);  // dark theme applied
    // Nonsense in the settings keeps the defaults.
    QSettings().setValue("preferences/defaultRays", "many");
    QSettings().setValue("preferences/lengthUnit", "furlong");
    QSettings().setValue("preferences/dragResolutionPercent", 5);  // below the 25 % floor
    Preferences::instance().load();
    QCOMPARE(Preferences::instance().values().defaultRays, 1500);
    QCOMPARE(Preferences::instance().values().dragResolutionPercent, 50);
    QCOMPARE(Preferences::instance().values().length, LengthUnit::Millimetre);
    Preferences::instance().setValues(PreferenceValues{});
  }
};

QTEST_MAIN(TestRecovery)

}  // namespace tst_recovery
#include "tst_recovery.moc"
