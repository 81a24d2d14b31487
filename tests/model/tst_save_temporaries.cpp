// Atomic saves and their leftovers (model/io/save_temporaries.h): a killed save's temporary
// file is removed at the next load, a save in progress (flock held) is not touched, saving
// through a symlink replaces the link's target, a directory is refused by name, and an
// unwritable path is reported before any work.
#include <QtTest>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/io/save_temporaries.h"
#include "model/scene/scene_io.h"
#include "tests/test_files.h"

namespace tst_save_temporaries {

using namespace fovea;
namespace fs = std::filesystem;

namespace {
fs::path freshDir(const char* name) {
  return fovea::testing::testTmpDir(std::string("save_temporaries/") + name, true);
}
using fovea::testing::readFileText;
}  // namespace

class TestSaveTemporaries : public QObject {
  Q_OBJECT
 private slots:
  void staleTemporariesAreRemovedAtLoad() {
    const fs::path dir = freshDir("stale");
    const fs::path scene = dir / "bench.json";
    std::ofstream(scene) << fovea::testing::prototypeSceneText();
    std::ofstream(dir / ".bench.json.tmp-AbC123") << "{\"half\":";  // a killed save
    std::ofstream(dir / ".other.json.tmp-AbC123") << "x";           // another file's: kept
    std::ofstream(dir / ".bench.json.tmp-toolong7") << "x";         // not a mkstemp name: kept
    // A save in progress elsewhere holds its lock: kept.
    const int busy = ::open((dir / ".bench.json.tmp-Busy99").c_str(), O_CREAT | O_WRONLY, 0600);
    QVERIFY(busy >= 0);
    QCOMPARE(::flock(busy, LOCK_EX), 0);

    const SceneLoadResult r = loadSceneFile(scene);
    QVERIFY(r.ok());
    QCOMPARE(int(r.warnings.size()), 1);
    QCOMPARE(QString::fromStdString(r.warnings[0]),
             QString("bench.json: removed .bench.json.tmp-AbC123, the temporary file of an interrupted save"));
    QVERIFY(!fs::exists(dir / ".bench.json.tmp-AbC123"));
    QVERIFY(fs::exists(dir / ".other.json.tmp-AbC123"));
    QVERIFY(fs::exists(dir / ".bench.json.tmp-toolong7"));
    QVERIFY(fs::exists(dir / ".bench.json.tmp-Busy99"));
    ::close(busy);  // the "other process" died: now it is a leftover
    QCOMPARE(int(removeStaleSaveTemporaries(scene).size()), 1);
    QVERIFY(!fs::exists(dir / ".bench.json.tmp-Busy99"));
  }

  void saveWritesThroughSymlinks() {
    const fs::path dir = freshDir("symlink");
    fs::create_directories(dir / "real");
    std::ofstream(dir / "real/scene.json") << "old";
    fs::create_symlink("real/scene.json", dir / "link.json");
    writeFileAtomic(dir / "link.json", "new\n");
    QVERIFY(fs::is_symlink(fs::symlink_status(dir / "link.json")));
    QCOMPARE(readFileText(dir / "real/scene.json"), std::string("new\n"));
    QCOMPARE(saveTarget(dir / "link.json"), dir / "real/scene.json");
    // A dangling link gets its target created.
    fs::create_symlink("real/new.json", dir / "dangling.json");
    writeFileAtomic(dir / "dangling.json", "created\n");
    QCOMPARE(readFileText(dir / "real/new.json"), std::string("created\n"));
    QVERIFY(fs::is_symlink(fs::symlink_status(dir / "dangling.json")));
  }

  void directoriesAndUnwritablePaths() {
    const fs::path dir = freshDir("dir");
    QVERIFY_THROWS_EXCEPTION(SceneIoError, writeFileAtomic(dir, "x"));
    try {
      writeFileAtomic(dir, "x");
    } catch (const SceneIoError& e) {
      QCOMPARE(QString(e.what()), QString::fromStdString(dir.string() + ": is a directory, not a file"));
    }
    QCOMPARE(cannotWriteFile(dir).value_or(""), std::string("is a directory, not a file"));
    QVERIFY(cannotWriteFile("/proc/x.pdf"));
    QVERIFY(cannotWriteFile("/nonexistent-dir/x.pdf"));
    QVERIFY(!cannotWriteFile(dir / "report.pdf"));
    QVERIFY(!fs::exists(dir / "report.pdf"));
    QCOMPARE(int(std::distance(fs::directory_iterator(dir), fs::directory_iterator())), 0);  // probe removed
    const SceneLoadResult r = loadSceneFile(dir);
    QCOMPARE(QString::fromStdString(r.errors.at(0)),
             QString::fromStdString(dir.string() + ": cannot read scene file: is a directory, not a file"));
  }
};

QTEST_GUILESS_MAIN(TestSaveTemporaries)

}  // namespace tst_save_temporaries
#include "tst_save_temporaries.moc"
