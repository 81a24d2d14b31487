// Scene files: the loader's messages for bad input, exact round trips, atomic saves.
#include <QtTest>
#include "tests/test_paths.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/embedded_scene.h"
#include "model/scene/scene_fields.h"
#include "model/scene/scene_io.h"
#include "model/scene/scene_parameters.h"

namespace tst_scene_io {

using namespace fovea;

namespace {
std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
std::string prototypeText() {
  return readText(std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json");
}

// Replace the first occurrence of `from` in the prototype text.
std::string edited(const std::string& from, const std::string& to) {
  std::string t = prototypeText();
  const auto at = t.find(from);
  if (at == std::string::npos) qFatal("fixture text not found: %s", from.c_str());
  return t.replace(at, from.size(), to);
}
// The 1-based line of the first occurrence of `what` in `text` (the parser's error position).
int lineOf(const std::string& text, const std::string& what) {
  const auto at = text.find(what);
  if (at == std::string::npos) qFatal("fixture text not found: %s", what.c_str());
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
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

  // The one loader the tests and benchmarks share gives the resource's scene, field for field
  // (the file is canonical: see below).
  void embeddedDefaultSceneIsTheResource() { QCOMPARE(serializeScene(embeddedDefaultScene()), prototypeText()); }

  void prototypeFileIsCanonical() {
    // The shipped file is in canonical form, so load -> save reproduces it byte for byte.
    SceneLoadResult r = parseScene(prototypeText(), "prototype-bench.json");
    QVERIFY(r.ok());
    QCOMPARE(serializeScene(*r.scene), prototypeText());
  }

  void everyShippedSceneRoundTripsByteForByte() {
    // The field table writes the canonical form: load -> save reproduces every shipped scene.
    int scenes = 0;
    for (const auto& e : std::filesystem::directory_iterator(std::string(FOVEA_SOURCE_DIR) + "/resources/scenes")) {
      if (e.path().extension() != ".json") continue;
      const std::string text = readText(e.path());
      SceneLoadResult r = parseScene(text, e.path().filename().string());
      QVERIFY2(r.ok(), e.path().c_str());
      QCOMPARE(r.warnings.size(), std::size_t{0});
      QCOMPARE(serializeScene(*r.scene), text);
      ++scenes;
    }
    QVERIFY(scenes >= 1);
  }

  void everyOptionalPartRoundTrips() {
    // Lens enabled (diverging), a phase-conjugate recording, unknown keys in nested objects and
    // in array elements, the view state set: save -> load -> save is a fixed point.
    Scene s = *parseScene(prototypeText(), "p").scene;
    s.lens.enabled = true;
    s.lens.focal_length_mm = -35.5;
    s.hoe_layers[2].recording.phase_conjugate = true;
    s.view.hoe_follows_gaze = true;
    // (in file order: the loader records unknown keys as it meets them)
    s.unknown["/projector/pixel_beam"]["m2"] = 1.1;
    s.unknown["/hoe_layers/1/recording"]["future"] = 3;
    s.unknown["/stages/2"]["note"] = "spare";
    const std::string saved = serializeScene(s);
    SceneLoadResult r = parseScene(saved, "s.json");
    QVERIFY(r.ok());
    QCOMPARE(r.warnings.size(), std::size_t{3});
    QVERIFY(*r.scene == s);
    QCOMPARE(serializeScene(*r.scene), saved);
  }

  void viewStateIsSavedWhenSet() {
    Scene s = *parseScene(prototypeText(), "p").scene;
    QVERIFY(!s.view.hoe_follows_gaze);
    QVERIFY(serializeScene(s).find("\"view\"") == std::string::npos);  // older files stay as they are
    s.view.hoe_follows_gaze = true;
    const std::string saved = serializeScene(s);
    QVERIFY(saved.find("  \"view\": {\n    \"hoe_follows_gaze\": true\n  }\n}") != std::string::npos);
    QVERIFY(parseScene(saved, "v").scene->view.hoe_follows_gaze);
    std::string bad = saved;
    bad.replace(bad.find("\"hoe_follows_gaze\": true"), 24, "\"hoe_follows_gaze\": 1");
    QCOMPARE(QString::fromStdString(parseScene(bad, "v.json").errors.at(0)),
             QString("v.json: view.hoe_follows_gaze: must be true or false, got a number (1)"));
  }

  void rangeNotation() {
    QCOMPARE(QString::fromStdString(Range::positive().text()), QString("> 0"));
    QCOMPARE(QString::fromStdString(Range::nonNegative().text()), QString(">= 0"));
    QCOMPARE(QString::fromStdString(Range::open(0, 180).text()), QString("(0, 180)"));
    QCOMPARE(QString::fromStdString(Range::closed(-1e5, 1e5).text()), QString("[-1e5, 1e5]"));
    QCOMPARE(QString::fromStdString(Range::openClosed(0, 10000).text()), QString("(0, 10000]"));
    QCOMPARE(QString::fromStdString(Range::openClosed(0, 10000).check(-5)), QString("must be > 0, got -5"));
    QCOMPARE(QString::fromStdString(Range::openClosed(0, 10000).check(10001)), QString("must be <= 10000, got 10001"));
    QCOMPARE(QString::fromStdString(Range::openClosed(0, 10000).check(10000)), QString());
    QCOMPARE(QString::fromStdString(Range::open(0, 15).check(15)), QString("must be in (0, 15), got 15"));
    QCOMPARE(QString::fromStdString(Range::closed(1, 4).checkInteger(7)), QString("must be in [1, 4], got 7"));
    QCOMPARE(QString::fromStdString(Range::any().check(std::nan(""))), QString("must be a finite number, got NaN"));
  }

  void everyNumberOutsideItsRangeIsRefused() {
    // The table drives validation: for every bounded number of every element, a value just
    // outside its range is refused with a message naming its path; a value inside is kept.
    const Scene base = *parseScene(prototypeText(), "p").scene;
    int checked = 0;
    for (const std::string& path : parameterPaths(base)) {
      Scene s = base;
      const std::string field = path.substr(0, path.find('[', path.find('.')));
      const auto fields = elementFields(s, path.substr(0, path.find('.')));
      const auto it = std::find_if(fields.begin(), fields.end(), [&](const SceneField& f) { return f.path == field; });
      QVERIFY2(it != fields.end(), path.c_str());
      const Range& range = it->info->range;
      if (range.low == Range::Bound::None) continue;
      const double outside = range.lo - 1.0;
      QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withParameter(s, path, outside));
      try {
        withParameter(s, path, outside);
      } catch (const std::invalid_argument& e) {
        QVERIFY2(std::string(e.what()).find(": " + path + ": must be") != std::string::npos, e.what());
      }
      QVERIFY(withParameter(s, path, parameterValue(s, path)) == s);
      ++checked;
    }
    QVERIFY(checked > 80);
  }

  void fieldLabelsAndPaths() {
    const Scene s = *parseScene(prototypeText(), "p").scene;
    QCOMPARE(QString::fromStdString(fieldLabel(s, "hoe_layers[1].thickness_um")), QString("Thickness"));
    QCOMPARE(QString::fromStdString(fieldLabel(s, "eye.gaze_deg[1]")), QString("Gaze pitch"));
    QCOMPARE(QString::fromStdString(fieldLabel(s, "stages[4].soft_limits_deg[0]")), QString("Soft limit low"));
    QCOMPARE(QString::fromStdString(fieldLabel(s, "stages[4].soft_limits_mm[0]")), QString());
    QCOMPARE(QString::fromStdString(fieldLabel(s, "hoe_layers[9].n0")), QString());
    QCOMPARE(parameterValue(s, "projector.pixels[0]"), 1280.0);
    QCOMPARE(withParameter(s, "projector.pixels[1]", 800).projector.pixels[1], 800);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withParameter(s, "projector.pixels[1]", 800.5));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withParameter(s, "projector.fov_deg[2]", 1));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withParameter(s, "projector.fov_deg", 1));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parameterValue(s, "projector.name"));
  }

  void roundTripKeepsUnknownKeys() {
    std::string t = edited("\"relief_mm\": 22.0,", "\"relief_mm\": 22.0,\n    \"future_key\": {\"a\": [1, 2]},");
    t = edited("\"name\": \"Optical bench prototype\",", "\"name\": \"Optical bench prototype\",\n  \"top_extra\": 7,");
    t.replace(t.find("\"relief_mm\": 22.0,"), 18, "\"relief_mm\": 22.0,\n    \"future_key\": {\"a\": [1, 2]},");
    SceneLoadResult r = parseScene(t, "x.json");
    QVERIFY(r.ok());
    QCOMPARE(r.warnings.size(), std::size_t{2});
    QVERIFY(r.warnings[0].find("top_extra") != std::string::npos ||
            r.warnings[1].find("top_extra") != std::string::npos);
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
    QTest::newRow("negative thickness") << QString::fromStdString(
                                               edited("\"name\": \"green\",\n      \"thickness_um\": 16.0",
                                                      "\"name\": \"green\",\n      \"thickness_um\": -5"))
                                        << "f.json: hoe_layers[1].thickness_um: must be > 0, got -5";
    QTest::newRow("mistyped field") << QString::fromStdString(edited("\"relief_mm\": 22.0", "\"relief_mm\": \"22\""))
                                    << "f.json: eye.relief_mm: must be a number, got a string";
    QTest::newRow("missing field") << QString::fromStdString(edited("\"pupil_diameter_mm\": 5.0,", ""))
                                   << "f.json: eye.pupil_diameter_mm: missing required field";
    QTest::newRow("null (NaN written by another tool)")
        << QString::fromStdString(edited("\"n0\": 1.5,", "\"n0\": null,"))
        << "f.json: hoe_layers[0].n0: must be a number, got null";
    QTest::newRow("n1 not below n0") << QString::fromStdString(edited("\"n1\": 0.015,", "\"n1\": 1.6,"))
                                     << "f.json: hoe_layers[0].n1: must be < n0 (1.5), got 1.6";
    QTest::newRow("out of range wavelength")
        << QString::fromStdString(edited("\"wavelength_nm\": 532.0", "\"wavelength_nm\": 5320"))
        << "f.json: hoe_layers[1].recording.wavelength_nm: must be in (200, 2000), got 5320";
    QTest::newRow("wrong array length") << QString::fromStdString(edited(
                                               "\"size_mm\": [\n      44.0,\n      36.0\n    ]", "\"size_mm\": [44.0]"))
                                        << "f.json: hoe.size_mm: must be an array of 2 numbers, got an array of 1";
    QTest::newRow("newer version")
        << QString::fromStdString(edited("\"version\": 1,", "\"version\": 7,"))
        << "f.json: version: file is version 7, this studio reads up to version 2 (update the studio)";
    const int relief_line = lineOf(prototypeText(), "\"relief_mm\"");  // moves when the scene gains a field
    QTest::newRow("overflow number")
        << QString::fromStdString(edited("\"relief_mm\": 22.0", "\"relief_mm\": 1e999"))
        << QString("f.json: malformed JSON at line %1, column 18: number overflow parsing '1e999'").arg(relief_line);
    QTest::newRow("malformed JSON") << QString::fromStdString(edited("\"relief_mm\": 22.0,", "\"relief_mm\": 22.0,,"))
                                    << QString(
                                           "f.json: malformed JSON at line %1, column 23: syntax error while "
                                           "parsing object key - unexpected ','; expected string literal")
                                           .arg(relief_line);
    QTest::newRow("not an object") << QString("[1, 2]")
                                   << "f.json: the top level must be a JSON object, got an array of 2";
    QTest::newRow("bad stage axis") << QString::fromStdString(edited("\"axis\": \"x\"", "\"axis\": \"w\""))
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
    QCOMPARE(QString::fromStdString(r.errors[0]),
             QString("/nonexistent/dir/scene.json: cannot read scene file: no such file"));
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

}  // namespace tst_scene_io
#include "tst_scene_io.moc"
