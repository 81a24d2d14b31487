// fovea-cli validate: exit codes and messages (good file, bad file with several problems,
// malformed JSON, missing file, missing argument).
#include <QtTest>
#include "tests/test_paths.h"

#include <QProcess>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_validate {

namespace {

struct Run {
  int exitCode = -1;
  QString out, err;
};

Run runCli(const QStringList& args) {
  const auto r = fovea::testing::runFoveaCli(args, 30000);
  return {r.code, QString::fromUtf8(r.out), QString::fromUtf8(r.err)};
}

std::string prototypeText() {
  std::ifstream in(std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

QString writeScene(const QString& name, std::string text,
                   const std::vector<std::pair<std::string, std::string>>& edits) {
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    if (at == std::string::npos) qFatal("fixture text not found: %s", from.c_str());
    text.replace(at, from.size(), to);
  }
  const auto path = fovea::testing::testTmpDir("cli_validate") / name.toStdString();
  std::ofstream(path) << text;
  return QString::fromStdString(path.string());
}

}  // namespace

class TestCliValidate : public QObject {
  Q_OBJECT
 private slots:
  void goodFileExitsZeroWithSummary() {
    const QString path = QString(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json";
    const Run r = runCli({"validate", path});
    QCOMPARE(r.exitCode, 0);
    const QStringList lines = r.out.split('\n', Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), 1);
    QCOMPARE(lines[0], path +
                           ": valid: Optical bench prototype: 3 HOE layers (660/532/460 nm), HOE 44x36 mm, projector "
                           "1280x720 px over 40x23.1 deg, eye relief 22 mm, pupil 5 mm, 5 stage axes");
  }

  void badFileListsEveryProblemOnItsOwnLine() {
    const QString path = writeScene(
        "bad.json", prototypeText(),
        {{"\"relief_mm\": 22.0", "\"relief_mm\": -5"},
         {"\"name\": \"green\",\n      \"thickness_um\": 16.0", "\"name\": \"green\",\n      \"thickness_um\": 0"},
         {"\"axis\": \"x\"", "\"axis\": \"w\""}});
    const Run r = runCli({"validate", path});
    QCOMPARE(r.exitCode, 1);
    const QStringList lines = r.out.split('\n', Qt::SkipEmptyParts);
    QCOMPARE(lines, QStringList({"bad.json: hoe_layers[1].thickness_um: must be > 0, got 0",
                                 "bad.json: eye.relief_mm: must be > 0, got -5",
                                 "bad.json: stages[0].axis: must be one of x, y, z, yaw, pitch, roll, got \"w\""}));
    QVERIFY2(r.err.contains("3 problem(s) in " + path), qPrintable(r.err));
  }

  void malformedJsonNamesLineAndColumn() {
    const QString path = writeScene("broken.json", "{\n  \"format\": \"fovea-scene\",\n  \"version\": 1,,\n}\n", {});
    const Run r = runCli({"validate", path});
    QCOMPARE(r.exitCode, 1);
    QVERIFY2(r.out.startsWith("broken.json: malformed JSON at line 3, column 16: "), qPrintable(r.out));
  }

  void missingFileExitsOne() {
    const Run r = runCli({"validate", "/nonexistent/scene.json"});
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out.trimmed(), QString("/nonexistent/scene.json: cannot read scene file: no such file"));
  }

  void missingArgumentIsUsageError() {
    const Run r = runCli({"validate"});
    QCOMPARE(r.exitCode, 2);
    QVERIFY2(r.err.contains("SCENE"), qPrintable(r.err));
  }

  void jsonOutput() {
    const QString path =
        writeScene("bad2.json", prototypeText(), {{"\"pupil_diameter_mm\": 5.0", "\"pupil_diameter_mm\": 0"}});
    const Run r = runCli({"validate", "--json", path});
    QCOMPARE(r.exitCode, 1);
    const QJsonObject o = QJsonDocument::fromJson(r.out.toUtf8()).object();
    QCOMPARE(o.value("valid").toBool(true), false);
    QCOMPARE(o.value("errors").toArray().size(), 1);
    QCOMPARE(o.value("errors").toArray()[0].toString(),
             QString("bad2.json: eye.pupil_diameter_mm: must be in (0, 15), got 0"));
  }
};

QTEST_GUILESS_MAIN(TestCliValidate)

}  // namespace tst_cli_validate
#include "tst_cli_validate.moc"
