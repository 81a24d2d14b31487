// The one output writer (model/io/output_file.h): refusals of an empty path and of non-regular
// targets (FIFO, device, directory) that stay what they were, a failed write reported with the
// path and strerror and the old file kept, the temporary file locked until the rename (a
// concurrent load's clean-up no longer deletes it), and the same file named twice.
#include <QtTest>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "model/io/output_file.h"
#include "model/io/save_temporaries.h"
#include "tests/test_files.h"

namespace tst_output_file {

using namespace fovea;
namespace fs = std::filesystem;

namespace {
fs::path freshDir(const char* name) {
  return fovea::testing::testTmpDir(std::string("output_file/") + name, true);
}

template <class F>
QString outputError(F f) {
  try {
    f();
  } catch (const OutputError& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}
}  // namespace

class TestOutputFile : public QObject {
  Q_OBJECT
 private slots:
  void refusesWhatIsNotARegularFile() {
    const fs::path dir = freshDir("refuse");
    QCOMPARE(outputError([] { writeOutputFile("", "x"); }), QString("an empty path names no file"));
    QCOMPARE(outputPathProblem("").value_or(""), std::string("an empty path names no file"));
    const fs::path fifo = dir / "pipe";
    QCOMPARE(::mkfifo(fifo.c_str(), 0600), 0);
    QCOMPARE(outputError([&] { writeOutputFile(fifo, "x"); }),
             QString::fromStdString(fifo.string() + ": is a FIFO, not a regular file (refusing to replace it)"));
    QVERIFY(fs::is_fifo(fifo));  // still a FIFO, not replaced by a regular file
    QCOMPARE(outputError([] { writeOutputFile("/dev/null", "x"); }),
             QString("/dev/null: is a character device, not a regular file (refusing to replace it)"));
    QVERIFY(fs::is_character_file("/dev/null"));
    QCOMPARE(outputError([&] { writeOutputFile(dir, "x"); }),
             QString::fromStdString(dir.string() + ": is a directory, not a file"));
    // Through a symlink to a device: the device is what would be replaced.
    fs::create_symlink("/dev/null", dir / "null-link");
    QVERIFY(outputError([&] { writeOutputFile(dir / "null-link", "x"); }).contains("character device"));
    QVERIFY(!outputPathProblem(dir / "new.json"));
    writeOutputFile(dir / "new.json", "new\n");
    QCOMPARE(fovea::testing::readFileText(dir / "new.json"), std::string("new\n"));
  }

  // A write that fails (here: past RLIMIT_FSIZE, EFBIG) names the path and the reason, leaves
  // the old file and no temporary file behind.
  void failedWriteKeepsTheOldFile() {
    const fs::path dir = freshDir("full");
    const fs::path target = dir / "out.json";
    std::ofstream(target) << "old";
    struct rlimit old {};
    QCOMPARE(::getrlimit(RLIMIT_FSIZE, &old), 0);
    const auto previous = std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit small = old;
    small.rlim_cur = 1000;
    QCOMPARE(::setrlimit(RLIMIT_FSIZE, &small), 0);
    const QString m = outputError([&] { writeOutputFile(target, std::string(100000, 'x')); });
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, previous);
    QCOMPARE(m, QString::fromStdString(target.string() +
                                       ": save failed (write: File too large); the existing file is unchanged"));
    QCOMPARE(fovea::testing::readFileText(target), std::string("old"));
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
    QCOMPARE(files, 1);
  }

  // A concurrent load clears unlocked temporary files; the save's own stays locked until its
  // rename, so the save completes (before: "rename: No such file or directory").
  void temporaryFileLockedUntilTheRename() {
    const fs::path dir = freshDir("lock");
    const fs::path target = dir / "scene.json";
    std::ofstream(target) << "old";
    std::size_t removed = 99;
    writeOutputFile(target, "new\n", [&] { removed = removeStaleSaveTemporaries(target).size(); });
    QCOMPARE(removed, std::size_t(0));
    QCOMPARE(fovea::testing::readFileText(target), std::string("new\n"));
    // The target's permissions are kept.
    fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
    writeOutputFile(target, "again\n");
    QCOMPARE(fs::status(target).permissions(), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  }

  void sameFileTwice() {
    const fs::path dir = freshDir("twice");
    const std::string a = (dir / "log.txt").string();
    QCOMPARE(sameOutputTwice({{"--trace", a}, {"--transcript", a}}).value_or(""),
             "--trace and --transcript name the same file (" + a + "): each output needs its own file");
    QVERIFY(sameOutputTwice({{"--trace", a}, {"--transcript", (dir / "." / "log.txt").string()}}));
    std::ofstream(a) << "x";
    fs::create_symlink(a, dir / "link.txt");
    QVERIFY(sameOutputTwice({{"--trace", a}, {"--transcript", (dir / "link.txt").string()}}));
    fs::create_hard_link(a, dir / "hard.txt");
    QVERIFY(sameOutputTwice({{"--trace", a}, {"--transcript", (dir / "hard.txt").string()}}));
    QVERIFY(!sameOutputTwice({{"--trace", a}, {"--transcript", (dir / "other.txt").string()}}));
    QVERIFY(!sameOutputTwice({{"--trace", a}, {"--transcript", ""}}));
  }
};

QTEST_GUILESS_MAIN(TestOutputFile)

}  // namespace tst_output_file
#include "tst_output_file.moc"
