// fovea-cli's inputs and outputs as hardened as the scene file (issue 28, docs/inputs-outputs.md):
// JSON to a full stdout is exit 1, never 0; output options refuse an empty path, devices and
// FIFOs (which stay what they were); seeds are 64-bit integers; a failed Slurm write prints no
// "wrote"; inputs are regular files of bounded size (devices and FIFOs refused at once, an image's
// header checked before decoding, a truncated JPEG refused); errors name the file and the key.
#include <QtTest>
#include "tests/test_paths.h"

#include <QProcess>
#include <QTemporaryDir>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "model/image/image_io.h"
#include "tests/cli/cli_process.h"
#include "tests/test_files.h"
#include "tests/tolerance_test_spec.h"

namespace tst_cli_io_hardening {

using fovea::testing::runFoveaCli;
using fovea::testing::writeTestFile;
namespace fs = std::filesystem;

namespace {

struct Full {
  int code = -1;
  QByteArray err;
};
// The command with its stdout on /dev/full (every write fails with ENOSPC).
Full toDevFull(const QStringList& args) {
  QProcess p;
  p.setStandardOutputFile("/dev/full");
  p.start(FOVEA_CLI_PATH, args);
  if (!p.waitForStarted()) return {};
  p.closeWriteChannel();
  const bool done = p.waitForFinished(120000);
  if (!done) p.kill(), p.waitForFinished(5000);
  return {done && p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardError()};
}

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}
std::string be32(std::uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}
std::string pngChunk(const std::string& type, const std::string& data) {
  return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc32(type + data));
}
// A PNG of a few hundred bytes whose header declares width x height grey pixels.
std::string pngBomb(std::uint32_t width, std::uint32_t height) {
  const QByteArray z = qCompress(QByteArray(4096, '\0'));
  const std::string idat(z.constData() + 4, std::size_t(z.size() - 4));  // qCompress: 4-byte length, then zlib
  return std::string("\x89PNG\r\n\x1a\n", 8) +
         pngChunk("IHDR", be32(width) + be32(height) + std::string("\x08\x00\x00\x00\x00", 5)) +
         pngChunk("IDAT", idat) + pngChunk("IEND", "");
}

// A tolerance part (shard 0 of 1) of the small spec with the given records.
QByteArray tolerancePart(const nlohmann::json& records) {
  nlohmann::json p{{"format", "fovea-tolerance-part"},
                   {"version", 1},
                   {"shard", {0, 1}},
                   {"scene", "s"},
                   {"scene_digest", "0"},
                   {"seed", 1},
                   {"trials", records.size()},
                   {"spec", nlohmann::json::parse(fovea::testing::smallToleranceSpec().toStdString())},
                   {"nominal",
                    {{"fov_min_deg", 90},
                     {"fov_zero_gaze_deg", 90},
                     {"eyebox_mm", 5},
                     {"inset_error_deg", 0},
                     {"mean_efficiency", 0.5}}},
                   {"records", records}};
  return QByteArray::fromStdString(p.dump());
}

}  // namespace

class TestCliIoHardening : public QObject {
  Q_OBJECT
 private slots:
  // Every command's JSON on a full disk: exit 1 naming stdout and strerror, not 0.
  void fullStdoutIsAnError() {
    QTemporaryDir dir;
    const QString scene =
        writeTestFile(dir, "scene.json", QByteArray::fromStdString(fovea::testing::prototypeSceneText()));
    const QString part = writeTestFile(
        dir, "part.json", tolerancePart({{{"trial", 0}, {"inputs", {0.1, 0.2}}, {"figures", {90, 90, 5, 0.1, 0.5}}}}));
    const QList<QStringList> commands{
        {"validate", scene, "--json"},
        {"format", scene},
        {"track", "--virtual", "1", "--json"},
        {"merge", part, "--json"},
        {"grating", "--n0", "1.5", "--n1", "0.02", "--thickness-um", "16", "--period-nm", "177.3", "--slant-deg", "0",
         "--probe-deg", "0", "--wavelength-nm", "532", "--json"},
    };
    for (const auto& args : commands) {
      const Full r = toDevFull(args);
      QVERIFY2(r.code == 1, qPrintable(args.join(' ') + ": exit " + QString::number(r.code) + "\n" + r.err));
      QVERIFY2(r.err.contains("stdout: write failed: No space left on device"),
               qPrintable(args.join(' ') + "\n" + r.err));
    }
  }

  // Output options: an empty path, a device, a FIFO or a directory are refused before any work
  // (exit 2) and stay what they were.
  void outputOptionsRefuseWhatIsNoFile() {
    QTemporaryDir dir;
    const QString fifo = dir.filePath("pipe");
    QCOMPARE(::mkfifo(fifo.toLocal8Bit().constData(), 0600), 0);
    const QString targets = writeTestFile(
        dir, "targets.json",
        R"({"format": "fovea-fit-targets", "version": 1, "targets": [{"id": "fov", "observable": "fov_deg", "value": 90, "sigma": 1}]})");
    const QString manifest = dir.filePath("none.json");
    struct Case {
      QStringList args;
      QString message;
    };
    const QList<Case> cases{
        {{"fit-targets", manifest, "--out", ""}, "--out: an empty path names no file"},
        {{"fit-targets", manifest, "--out", "/dev/null"}, "--out: /dev/null: is a character device"},
        {{"fit-targets", manifest, "--out", fifo}, "is a FIFO, not a regular file"},
        {{"fit-targets", manifest, "--out", dir.path()}, "is a directory, not a file"},
        {{"color-calibrate", "--measurements", manifest, "--out", ""}, "--out: an empty path names no file"},
        {{"color-calibrate", "--measurements", manifest, "--out", "/dev/null"}, "is a character device"},
        {{"fit", "--targets", targets, "--free", "eye.relief_mm", "--write-scene", "/dev/null"},
         "--write-scene: /dev/null: is a character device"},
        {{"fit", "--targets", targets, "--free", "eye.relief_mm", "--write-scene", ""},
         "--write-scene: an empty path names no file"},
    };
    for (const auto& c : cases) {
      const auto r = runFoveaCli(c.args, 60000);
      QVERIFY2(r.code == 2, qPrintable(c.args.join(' ') + ": exit " + QString::number(r.code) + "\n" + r.err));
      QVERIFY2(r.err.contains(c.message.toUtf8()), qPrintable(c.args.join(' ') + "\n" + r.err));
    }
    QVERIFY(fs::is_character_file("/dev/null"));
    QVERIFY(fs::is_fifo(fifo.toStdString()));
  }

  // The same file for two outputs of one command line: refused (exit 2) before any work, the
  // file untouched: composite wrote its three images one over the other and exited 0.
  void sameOutputTwiceRefused() {
    QTemporaryDir dir;
    const QString kept = writeTestFile(dir, "kept.png", "not replaced");
    const QString other = dir.filePath("other.png");
    // Spelt differently, the same file: dir/./kept.png.
    const QString respelt = dir.path() + "/./kept.png";
    struct Case {
      QStringList args;
      QString message;
    };
    const QList<Case> cases{
        {{"composite", "--image", dir.filePath("none.png"), "--gaze-deg", "0,0", "--out-foveal", kept,
          "--out-peripheral", other, "--out-perceived", respelt},
         "--out-foveal and --out-perceived name the same file (" + respelt + "): each output needs its own file"},
        {{"composite", "--image", dir.filePath("none.png"), "--gaze-deg", "0,0", "--out-foveal", other,
          "--out-peripheral", kept, "--out-perceived", dir.filePath("third.png")},
         ""},  // distinct: passes the check, then fails on the missing image (exit 1)
        {{"composite", "--image", dir.filePath("none.png"), "--gaze-deg", "0,0", "--out-foveal", "", "--out-peripheral",
          kept, "--out-perceived", other},
         "--out-foveal: an empty path names no file"},
        {{"stage", "--virtual", "MTS25-Z8", "--trace", kept, "--transcript", respelt, "move-abs", "1"},
         "--trace and --transcript name the same file"},
    };
    for (const auto& c : cases) {
      const auto r = runFoveaCli(c.args, 60000);
      if (c.message.isEmpty()) {
        QVERIFY2(r.code == 1, qPrintable(c.args.join(' ') + ": exit " + QString::number(r.code) + "\n" + r.err));
        QVERIFY2(r.err.contains("none.png"), r.err.constData());
        continue;
      }
      QVERIFY2(r.code == 2, qPrintable(c.args.join(' ') + ": exit " + QString::number(r.code) + "\n" + r.err));
      QVERIFY2(r.err.contains(c.message.toUtf8()), qPrintable(c.args.join(' ') + "\n" + r.err));
      QFile f(kept);
      QVERIFY(f.open(QIODevice::ReadOnly));
      QCOMPARE(f.readAll(), QByteArray("not replaced"));
      QVERIFY(!QFile::exists(other));
    }
  }

  // --seed: a 64-bit unsigned integer, never wrapped (-1 was 2^64 - 1) nor rounded (1e23).
  void seedsAreValidated() {
    QTemporaryDir dir;
    const QString spec = writeTestFile(dir, "spec.json", fovea::testing::smallToleranceSpec());
    for (const char* seed : {"-1", "18446744073709551616", "1e23", "1.5", "", "0x10"}) {
      const auto r = runFoveaCli({"tolerance", "--spec", spec, "--trials", "1", "--seed", seed, "--json"}, 60000);
      QVERIFY2(r.code == 2, qPrintable(QString(seed) + ": exit " + QString::number(r.code)));
      QVERIFY2(r.err.contains("--seed: expected an integer in [0, 18446744073709551615]"), r.err.constData());
    }
    const auto track = runFoveaCli({"track", "--virtual", "1", "--seed", "4294967296", "--json"}, 60000);
    QCOMPARE(track.code, 2);
    QVERIFY2(track.err.contains("--seed: expected an integer in [0, 4294967295]"), track.err.constData());
    const auto ok = runFoveaCli({"track", "--virtual", "1", "--seed", "4294967295", "--json"}, 60000);
    QCOMPARE(ok.code, 0);
    QCOMPARE(nlohmann::json::parse(ok.out.toStdString())["seed"].get<std::uint64_t>(), std::uint64_t(4294967295u));
  }

  // The spec's errors name the file and the key; integers do not wrap.
  void toleranceSpecErrorsNameFileAndKey() {
    QTemporaryDir dir;
    auto run = [&](const char* name, const nlohmann::json& patch) {
      nlohmann::json j = nlohmann::json::parse(fovea::testing::smallToleranceSpec().toStdString());
      j.merge_patch(patch);
      const QString spec = writeTestFile(dir, name, QByteArray::fromStdString(j.dump()));
      return runFoveaCli({"tolerance", "--spec", spec, "--trials", "2", "--json"}, 60000);
    };
    auto r = run("wrap.json", {{"optimiser", {{"edge_bisections", 4294967299ULL}}}});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("wrap.json: optimiser.edge_bisections: must be an integer in [0, 20], got 4294967299"),
             r.err.constData());
    r = run("trunc.json", {{"optimiser", {{"bracket_points", 9.9}}}});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("trunc.json: optimiser.bracket_points: must be an integer in [3, 65], got 9.9"),
             r.err.constData());
    r = run("far.json", {{"gaze", {{"from_deg", 1e300}, {"to_deg", 1e300}}}});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("far.json: gaze.from_deg: must be in [-80, 80]"), r.err.constData());
    r = run("type.json", {{"target_yield", "high"}});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("type.json: target_yield: must be a number, got a string"), r.err.constData());
    QVERIFY(!r.err.contains("json.exception"));
    nlohmann::json pixels = nlohmann::json::parse(fovea::testing::smallToleranceSpec().toStdString());
    pixels["parameters"][0]["path"] = "projector.pixels[0]";
    const QString spec = writeTestFile(dir, "pixels.json", QByteArray::fromStdString(pixels.dump()));
    r = runFoveaCli({"tolerance", "--spec", spec, "--trials", "2", "--json"}, 60000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("pixels.json: parameters[0].path: \"projector.pixels[0]\" is an integer field"),
             r.err.constData());
  }

  // A part whose records are shorter than the spec: refused naming the file and the key.
  void mergeRefusesShortRecords() {
    QTemporaryDir dir;
    const QString empty = writeTestFile(
        dir, "empty.json",
        tolerancePart({{{"trial", 0}, {"inputs", nlohmann::json::array()}, {"figures", nlohmann::json::array()}}}));
    auto r = runFoveaCli({"merge", empty, "--json"}, 60000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("empty.json: records[0].inputs: must be an array of 2 numbers"), r.err.constData());
    const QString shorter =
        writeTestFile(dir, "short.json", tolerancePart({{{"trial", 0}, {"inputs", {0.1, 0.2}}, {"figures", {90}}}}));
    r = runFoveaCli({"merge", shorter, "--json"}, 60000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("short.json: records[0].figures: must be an array of 5 numbers"), r.err.constData());
    // Non-finite figures (null in the part) are counted, not binned.
    const QString nulls =
        writeTestFile(dir, "null.json",
                      tolerancePart({{{"trial", 0}, {"inputs", {0.1, 0.2}}, {"figures", {nullptr, 90, 5, 0.1, 0.5}}},
                                     {{"trial", 1}, {"inputs", {0.1, 0.2}}, {"figures", {80, 90, 5, 0.1, 0.5}}}}));
    r = runFoveaCli({"merge", nulls, "--json"}, 60000);
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["figures"]["fov_min_deg"]["non_finite"].get<int>(), 1);
    QCOMPARE(j["figures"]["fov_min_deg"]["count"].get<int>(), 1);
  }

  // --slurm DIR where a script cannot be written: exit 1 naming it, no "wrote".
  void slurmWriteFailureSaysSo() {
    QTemporaryDir dir;
    const QString spec = writeTestFile(dir, "spec.json", fovea::testing::smallToleranceSpec());
    const QString job = dir.filePath("job");
    fs::create_directories((job + "/tolerance.sbatch").toStdString());  // a directory where the script goes
    const auto r = runFoveaCli({"tolerance", "--spec", spec, "--trials", "4", "--slurm", job}, 60000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("tolerance.sbatch: is a directory, not a file"), r.err.constData());
    QVERIFY(!r.out.contains("wrote"));
  }

  // Inputs: devices and FIFOs refused at once (no read of /dev/zero, no wait for a writer), an
  // image's declared size checked before it is decoded, a truncated JPEG refused.
  void inputsAreRegularBoundedFiles() {
    QTemporaryDir dir;
    const QString fifo = dir.filePath("pipe.png");
    QCOMPARE(::mkfifo(fifo.toLocal8Bit().constData(), 0600), 0);
    auto r = runFoveaCli({"track", "/dev/zero", "--json"}, 30000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("/dev/zero: is a device or a socket, not a regular file"), r.err.constData());
    r = runFoveaCli({"track", fifo, "--json"}, 30000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("is a FIFO, not a regular file"), r.err.constData());
    const QString bomb = writeTestFile(dir, "bomb.png", QByteArray::fromStdString(pngBomb(20000, 20000)));
    QVERIFY(QFileInfo(bomb).size() < 1000);
    r = runFoveaCli({"track", bomb, "--json"}, 30000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("bomb.png: the header declares 20000 x 20000 pixels, more than the limit of 50 Mpixel"),
             r.err.constData());
    // A complete JPEG tracks; the same file cut in half is refused, not tracked as a frame.
    cv::Mat grey(120, 160, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
    const QString jpeg = dir.filePath("eye.jpg");
    fovea::image::writeLinearRgb(jpeg.toStdString(), grey);
    r = runFoveaCli({"track", jpeg, "--json"}, 30000);
    QVERIFY2(r.code == 0, r.err.constData());
    QFile full(jpeg);
    QVERIFY(full.open(QIODevice::ReadOnly));
    const QByteArray bytes = full.readAll();
    const QString cut = writeTestFile(dir, "cut.jpg", bytes.left(bytes.size() / 2));
    r = runFoveaCli({"track", cut, "--json"}, 30000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("cut.jpg: truncated JPEG (no end-of-image marker)"), r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["frames"][0]["found"].get<bool>(), false);
    // The colour CSV and the JSON inputs: the same refusals.
    r = runFoveaCli({"color-calibrate", "--measurements", "/dev/zero", "--out", dir.filePath("cal.json")}, 30000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("/dev/zero: cannot read the measurements: is a character device, not a regular file"),
             r.err.constData());
    r = runFoveaCli({"tolerance", "--spec", fifo, "--trials", "1"}, 30000);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("is a FIFO, not a regular file"), r.err.constData());
    r = runFoveaCli({"validate", "/dev/zero"}, 30000);  // validate lists the problems on stdout
    QCOMPARE(r.code, 1);
    QVERIFY2(r.out.contains("/dev/zero: cannot read scene file: is a character device, not a regular file"),
             r.out.constData());
    QVERIFY2(r.err.contains("1 problem(s) in /dev/zero"), r.err.constData());
  }
};

QTEST_GUILESS_MAIN(TestCliIoHardening)

}  // namespace tst_cli_io_hardening
#include "tst_cli_io_hardening.moc"
