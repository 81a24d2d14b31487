// Scene files: the loader's messages for bad input, exact round trips, atomic saves.
#include <QtTest>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/embedded_scene.h"
#include "model/scene/scene_io.h"

using namespace fovea;

namespace {
std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
std::string prototypeText() { return readText(std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json"); }

// Replace the first occurrence of `from` in the prototype text.
std::string edited(const std::string& from, const std::string& to) {
  std::string t = prototypeText();
  const auto at = t.find(from);
  if (at == std::string::npos) qFatal("fixture text not found: %s", from.c_str());
  return t.replace(at, from.size(), to);
}
std::filesystem::path tmpDir() {
  auto d = std::filesystem::path(qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp").toStdString()) / "scene_io";
  std::filesystem::create_directories(d);
  return d;
}
}  // namespace

class TestSceneIo : public QObject {
  Q_OBJECT
 private slots:
  void prototypeLoads() {
    SceneLoadResult r = parseScene(prototypeText(), "prototype-bench.json");
    QVERIFY2(r.ok(), r.errors.empty() ? "" : r.errors.front().c_str());
    QCOMPARE(r.warnings.size(), std::size_t{0});
    const Scene& s = *r.scene;
    QCOMPARE(s.eye.relief_mm, 22.0);
    QCOMPARE(s.eye.pupil_diameter_mm, 5.0);
    QCOMPARE(s.eye.eyeball_diameter_mm, 23.0);
    QCOMPARE(s.hoe_layers.size(), std::size_t{3});
    QCOMPARE(s.hoe_layers[0].recording.wavelength_nm, 660.0);
    QCOMPARE(s.hoe_layers[1].recording.wavelength_nm, 532.0);
    QCOMPARE(s.hoe_layers[2].recording.wavelength_nm, 460.0);
    QCOMPARE(s.eye.gaze_range_deg[0], -20.0);
    QCOMPARE(s.stages.size(), std::size_t{5});
    QCOMPARE(s.stages[4].axis, std::string("yaw"));
    QCOMPARE(s.stages[4].soft_limits[1], 25.0);
  }

  void embeddedEqualsResource() { QCOMPARE(std::string(embeddedDefaultSceneJson()), prototypeText()); }

  void prototypeFileIsCanonical() {
    // The shipped file is in canonical form, so load -> save reproduces it byte for byte.
    SceneLoadResult r = parseScene(prototypeText(), "prototype-bench.json");
    QVERIFY(r.ok());
    QCOMPARE(serializeScene(*r.scene), prototypeText());
  }

  void roundTripKeepsUnknownKeys() {
    std::string t = edited("\"relief_mm\": 22.0,", "\"relief_mm\": 22.0,\n    \"future_key\": {\"a\": [1, 2]},");
    t = edited("\"name\": \"Optical bench prototype\",", "\"name\": \"Optical bench prototype\",\n  \"top_extra\": 7,");
    t.replace(t.find("\"relief_mm\": 22.0,"), 18, "\"relief_mm\": 22.0,\n    \"future_key\": {\"a\": [1, 2]},");
    SceneLoadResult r = parseScene(t, "x.json");
    QVERIFY(r.ok());
    QCOMPARE(r.warnings.size(), std::size_t{2});
    QVERIFY(r.warnings[0].find("top_extra") != std::string::npos || r.warnings[1].find("top_extra") != std::string::npos);
    const std::string saved = serializeScene(*r.scene);
    QVERIFY(saved.find("\"future_key\"") != std::string::npos);
    QVERIFY(saved.find("\"top_extra\": 7") != std::string::npos);
    SceneLoadResult again = parseScene(saved, "saved.json");
    QVERIFY(again.ok());
    QVERIFY(*again.scene == *r.scene);
    QCOMPARE(serializeScene(*again.scene), saved);
  }

  void badInput_data() {
    QTest::addColumn<QString>("text");
    QTest::addColumn<QString>("message");
    QTest::newRow("negative thickness")
        << QString::fromStdString(edited("\"name\": \"green\",\n      \"thickness_um\": 16.0", "\"name\": \"green\",\n      \"thickness_um\": -5"))
        << "f.json: hoe_layers[1].thickness_um: must be > 0, got -5";
    QTest::newRow("mistyped field") << QString::fromStdString(edited("\"relief_mm\": 22.0", "\"relief_mm\": \"22\""))
                                    << "f.json: eye.relief_mm: must be a number, got a string";
    QTest::newRow("missing field") << QString::fromStdString(edited("\"pupil_diameter_mm\": 5.0,", ""))
                                   << "f.json: eye.pupil_diameter_mm: missing required field";
    QTest::newRow("null (NaN written by another tool)")
        << QString::fromStdString(edited("\"n0\": 1.5,", "\"n0\": null,"))
        << "f.json: hoe_layers[0].n0: must be a number, got null";
    QTest::newRow("n1 not below n0")
        << QString::fromStdString(edited("\"n1\": 0.015,", "\"n1\": 1.6,"))
        << "f.json: hoe_layers[0].n1: must be < n0 (1.5), got 1.6";
    QTest::newRow("out of range wavelength")
        << QString::fromStdString(edited("\"wavelength_nm\": 532.0", "\"wavelength_nm\": 5320"))
        << "f.json: hoe_layers[1].recording.wavelength_nm: must be in (200, 2000), got 5320";
    QTest::newRow("wrong array length")
        << QString::fromStdString(edited("\"size_mm\": [\n      44.0,\n      36.0\n    ]", "\"size_mm\": [44.0]"))
        << "f.json: hoe.size_mm: must be an array of 2 numbers, got an array of 1";
    QTest::newRow("newer version") << QString::fromStdString(edited("\"version\": 1,", "\"version\": 7,"))
                                   << "f.json: version: file is version 7, this studio reads up to version 1 (update the studio)";
    QTest::newRow("overflow number")
        << QString::fromStdString(edited("\"relief_mm\": 22.0", "\"relief_mm\": 1e999"))
        << "f.json: malformed JSON at line 159, column 18: number overflow parsing '1e999'";
    QTest::newRow("malformed JSON")
        << QString::fromStdString(edited("\"relief_mm\": 22.0,", "\"relief_mm\": 22.0,,"))
        << "f.json: malformed JSON at line 159, column 23: syntax error while parsing object key - unexpected ','; expected string literal";
    QTest::newRow("not an object") << QString("[1, 2]") << "f.json: the top level must be a JSON object, got an array of 2";
    QTest::newRow("bad stage axis")
        << QString::fromStdString(edited("\"axis\": \"x\"", "\"axis\": \"w\""))
        << "f.json: stages[0].axis: must be one of x, y, z, yaw, pitch, roll, got \"w\"";
  }
  void badInput() {
    QFETCH(QString, text);
    QFETCH(QString, message);
    SceneLoadResult r = parseScene(text.toStdString(), "f.json");
    QVERIFY(!r.ok());
    QVERIFY(!r.scene.has_value());
    QCOMPARE(QString::fromStdString(r.errors.front()), message);
  }

  void allProblemsReported() {
    std::string t = edited("\"relief_mm\": 22.0", "\"relief_mm\": -1");
    t.replace(t.find("\"pupil_diameter_mm\": 5.0"), 24, "\"pupil_diameter_mm\": 0");
    SceneLoadResult r = parseScene(t, "f.json");
    QCOMPARE(r.errors.size(), std::size_t{2});
    QCOMPARE(QString::fromStdString(r.errors[0]), QString("f.json: eye.pupil_diameter_mm: must be in (0, 15), got 0"));
    QCOMPARE(QString::fromStdString(r.errors[1]), QString("f.json: eye.relief_mm: must be > 0, got -1"));
  }

  void validateCatchesNaN() {
    Scene s = *parseScene(prototypeText(), "p").scene;
    s.hoe.pose.position_mm[1] = std::nan("");
    auto problems = validateScene(s);
    QCOMPARE(problems.size(), std::size_t{1});
    QCOMPARE(QString::fromStdString(problems[0]), QString("hoe.position_mm[1]: must be a number, got null"));
  }

  void unreadableFile() {
    SceneLoadResult r = loadSceneFile("/nonexistent/dir/scene.json");
    QVERIFY(!r.ok());
    QCOMPARE(QString::fromStdString(r.errors[0]), QString("/nonexistent/dir/scene.json: cannot read scene file: no such file"));
  }

  void atomicSaveSurvivesFailure() {
    const auto path = tmpDir() / "atomic.json";
    Scene s = *parseScene(prototypeText(), "p").scene;
    saveSceneFileAtomic(s, path);
    const std::string before = readText(path);
    QCOMPARE(before, prototypeText());
    Scene changed = s;
    changed.eye.relief_mm = 30.0;
    // Simulated crash between writing the temporary file and renaming it.
    bool threw = false;
    try {
      saveSceneFileAtomic(changed, path, [] { throw SceneIoError("simulated power cut"); });
    } catch (const SceneIoError& e) {
      threw = std::string(e.what()) == "simulated power cut";
    }
    QVERIFY(threw);
    QCOMPARE(readText(path), before);
    // No temporary file left behind.
    int entries = 0;
    for (auto& e : std::filesystem::directory_iterator(tmpDir())) entries += e.path().filename() != "atomic.json";
    QCOMPARE(entries, 0);
    // A directory that cannot be written: clear error, nothing created.
    bool failed = false;
    try {
      saveSceneFileAtomic(changed, "/proc/fovea-cannot-write.json");
    } catch (const SceneIoError& e) {
      failed = std::string(e.what()).find("/proc/fovea-cannot-write.json: cannot create a temporary file") == 0;
    }
    QVERIFY(failed);
    saveSceneFileAtomic(changed, path);
    QCOMPARE(parseScene(readText(path), "a").scene->eye.relief_mm, 30.0);
  }
};

QTEST_GUILESS_MAIN(TestSceneIo)
#include "tst_scene_io.moc"
