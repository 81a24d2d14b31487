// Bad input never crashes, never hangs and never lies: the reproducers of the adversarial run
// against fovea-cli, each with the message it now gives (deep nesting, output blow-up, invalid
// UTF-8, batch lines, directories, duplicate keys, leftovers of killed saves, symlinks,
// unwritable report paths, Kogelnik at its extremes, degenerate periods).
#include <QtTest>

#include <QElapsedTimer>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_bad_input {

namespace {
namespace fs = std::filesystem;
using fovea::testing::CliOutput;

CliOutput runCli(const QStringList& args, const QByteArray& stdin_data = {}) {
  return fovea::testing::runFoveaCli(args, 120000, stdin_data);
}

fs::path tmpDir() {
  return fovea::testing::testTmpDir("cli_bad_input");
}
using fovea::testing::prototypeSceneText;
using fovea::testing::readFileText;

// The prototype with `insert` right after its "notes": { (on line 5).
QString sceneWith(const std::string& name, const std::string& insert) {
  std::string text = prototypeSceneText();
  const std::string anchor = "\"notes\": {";
  text.replace(text.find(anchor), anchor.size(), anchor + insert);
  const fs::path p = tmpDir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return QString::fromStdString(p.string());
}

std::string deep(std::size_t n) {
  return std::string(n, '[') + std::string(n, ']');
}

const QByteArray kRequest =
    R"({"n0":1.5,"n1":0.02,"thickness_um":16,"period_nm":177.33333333333334,"slant_deg":0,"probe_deg":0,"wavelength_nm":532})";

QList<QByteArray> outLines(const CliOutput& r) {
  return r.out.trimmed().split('\n');
}
}  // namespace

class TestCliBadInput : public QObject {
  Q_OBJECT
 private slots:
  // 100 000-deep array in a scene: SIGSEGV before; now one message naming line and column.
  void deepNestingInAScene() {
    const QString path = sceneWith("deep.json", "\"deep\": " + deep(100000) + ",");
    const QString expected = "deep.json: line 5, column 83: nesting deeper than 64";
    for (const QStringList& args :
         {QStringList{"validate", path}, QStringList{"format", path}, QStringList{"trace", path, "--json"}}) {
      const CliOutput r = runCli(args);
      QCOMPARE(r.code, 1);
      QVERIFY2((r.out + r.err).contains(expected.toUtf8()), (r.out + r.err).left(300).constData());
    }
  }

  // A 50 000-deep `notes` made format -i write 5 GB: now refused at the reader; a file within
  // the depth limit whose canonical form would still explode is refused before any write.
  void formatNeverBlowsUp() {
    const QString deep_path = sceneWith("deep_notes.json", "\"n\": " + deep(50000) + ",");
    QCOMPARE(runCli({"format", "-i", deep_path}).code, 1);
    std::string wide = "\"n\": " + std::string(60, '[');
    for (int i = 0; i < 20000; ++i) wide += i ? ",[]" : "[]";
    wide += std::string(60, ']') + ",";
    const QString path = sceneWith("wide_notes.json", wide);
    const auto before = fs::file_size(path.toStdString());
    const CliOutput r = runCli({"format", "-i", path});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("more than 16 times the file's") && r.err.contains("refused"), r.err.constData());
    QCOMPARE(fs::file_size(path.toStdString()), before);  // untouched
  }

  // One bad line used to end the batch (deep value dumped into the message, invalid UTF-8 in
  // the error text): now every line answers, errors name the line, exit 1.
  void batchLinesNeverStopTheBatch() {
    QByteArray in = kRequest + "\n";
    in += QByteArray::fromStdString("{\"n0\":" + deep(100000) + "}\n");
    in += "{\"n0\":\"\xFF\xFE\"}\n";
    in += "\n";
    in += QByteArray::fromStdString("{\"n0\":" + deep(30) + "," + kRequest.mid(1).toStdString() + "\n");
    in += kRequest;  // no final newline
    const CliOutput r = runCli({"grating", "--batch", "-"}, in);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("--batch: 4 of 6 line(s) failed"), r.err.constData());
    const auto lines = outLines(r);
    QCOMPARE(lines.size(), 6);
    std::vector<nlohmann::json> j;
    for (const auto& l : lines) j.push_back(nlohmann::json::parse(l.toStdString()));  // all valid JSON
    QVERIFY(j[0].contains("efficiency"));
    QCOMPARE(QString::fromStdString(j[1]["error"]), QString("line 2: column 70: nesting deeper than 64"));
    QCOMPARE(QString::fromStdString(j[2]["error"]), QString("line 3: column 8: invalid UTF-8 at byte offset 7"));
    QCOMPARE(QString::fromStdString(j[3]["error"]), QString("line 4: blank line (expected a JSON object)"));
    QCOMPARE(QString::fromStdString(j[4]["error"]),
             QString("line 5: column 68: duplicate key \"n0\" (first at column 2)"));
    QVERIFY(j[5].contains("efficiency"));
    QCOMPARE(j[2]["line"].get<int>(), 3);
  }

  void batchDirectoryIsRefused() {
    const CliOutput r = runCli({"grating", "--batch", QString::fromStdString(tmpDir().string())});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("is a directory, not a file of JSON lines"), r.err.constData());
  }

  // validate --json printed nothing for invalid UTF-8 (the message held the raw bytes).
  void validateJsonAlwaysPrintsJson() {
    std::string text = prototypeSceneText();
    text.replace(text.find("Optical bench prototype"), 7,
                 "Opt\xC3\x28\xFF"
                 "cal");
    const fs::path p = tmpDir() / "utf8.json";
    std::ofstream(p, std::ios::binary) << text;
    const CliOutput r = runCli({"validate", "--json", QString::fromStdString(p.string())});
    QCOMPARE(r.code, 1);
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["valid"].get<bool>(), false);
    const std::size_t at = prototypeSceneText().find("Optical bench prototype") + 3;
    QCOMPARE(QString::fromStdString(j["errors"][0]),
             QString("utf8.json: line 4, column 15: invalid UTF-8 at byte offset %1").arg(at));
  }

  void duplicateKeysAreRejected() {
    std::string text = prototypeSceneText();
    text.replace(text.find("\"version\": 1,"), 13, "\"version\": 2, \"version\": 1,");
    const fs::path p = tmpDir() / "dup.json";
    std::ofstream(p) << text;
    const CliOutput r = runCli({"validate", QString::fromStdString(p.string())});
    QCOMPARE(r.code, 1);
    QCOMPARE(r.out.trimmed(),
             QByteArray("dup.json: line 3, column 17: duplicate key \"version\" (first at line 3, column 3)"));
  }

  void directoryIsNotMalformedJson() {
    const CliOutput r = runCli({"validate", QString::fromStdString(tmpDir().string())});
    QCOMPARE(r.code, 1);
    QCOMPARE(r.out.trimmed(),
             QByteArray::fromStdString(tmpDir().string() + ": cannot read scene file: is a directory, not a file"));
  }

  // 11 s and no path before; now refused before the studio starts.
  void reportToAnUnwritablePathFailsFast() {
    QElapsedTimer t;
    t.start();
    const CliOutput r = runCli({"report", "--out", "/proc/x.pdf"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--out: cannot write '/proc/x.pdf': "), r.err.constData());
    qInfo("report --out /proc/x.pdf refused in %lld ms", t.elapsed());
  }

  void staleTemporariesAreRemovedAtStart() {
    const fs::path dir = tmpDir() / "stale";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "s.json") << prototypeSceneText();
    std::ofstream(dir / ".s.json.tmp-k9Xq2Z") << prototypeSceneText().substr(0, 1000);  // a save killed mid-write
    const CliOutput r = runCli({"validate", QString::fromStdString((dir / "s.json").string())});
    QCOMPARE(r.code, 0);
    QVERIFY2(r.err.contains("warning: s.json: removed .s.json.tmp-k9Xq2Z, the temporary file of an interrupted save"),
             r.err.constData());
    QVERIFY(!fs::exists(dir / ".s.json.tmp-k9Xq2Z"));
  }

  void formatInPlaceWritesThroughSymlinks() {
    const fs::path dir = tmpDir() / "link";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string compact = prototypeSceneText();
    compact.replace(compact.find("\"version\": 1"), 12, "\"version\":1");  // not canonical
    std::ofstream(dir / "target.json") << compact;
    fs::create_symlink("target.json", dir / "link.json");
    const CliOutput r = runCli({"format", "-i", QString::fromStdString((dir / "link.json").string())});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY(fs::is_symlink(fs::symlink_status(dir / "link.json")));
    QVERIFY(readFileText(dir / "target.json").find("\"version\": 1") != std::string::npos);
  }

  // n1 = 0 gave efficiency 1 and zero order 1 at this extreme; both are 0 (the probe is absorbed).
  void zeroModulationAtTheExtreme() {
    const CliOutput r = runCli({"grating", "--n0", "1.5", "--n1", "0", "--thickness-um", "16", "--period-nm", "177.3",
                                "--slant-deg", "0", "--probe-deg", "89.9999999999", "--wavelength-nm", "532",
                                "--absorption-per-mm", "1e300", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["efficiency"].get<double>(), 0.0);
    QCOMPARE(j["zero_order"].get<double>(), 0.0);
  }

  // period_nm 1e-300 printed null for xi and c_s.
  void degeneratePeriodIsAnError() {
    const CliOutput r = runCli({"grating", "--n0", "1.5", "--n1", "0.02", "--thickness-um", "16", "--period-nm",
                                "1e-300", "--slant-deg", "0", "--probe-deg", "0", "--wavelength-nm", "532", "--json"});
    QCOMPARE(r.code, 2);
    QCOMPARE(r.err.trimmed(), QByteArray("fovea-cli: --period-nm: degenerate fringe period: must be at least 1e-6 "
                                         "wavelengths (got 1e-300 nm at 532 nm)"));
    QVERIFY(r.out.isEmpty());
  }
};

QTEST_GUILESS_MAIN(TestCliBadInput)

}  // namespace tst_cli_bad_input
#include "tst_cli_bad_input.moc"
