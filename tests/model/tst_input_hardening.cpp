// The inputs of issue 28 at the model level: tolerance statistics with non-finite figures
// (counted, never binned), merges of parts whose records do not have the spec's shape, the
// tolerance spec's typed fields (integers without wrap or truncation, gazes in range, bounded
// gaze lists), fit targets' ranges, a manifest with a step captured twice, the colour CSV's
// header and luminance rules, the --free window clipped before its margin, and the one
// field reader (model/io/json_fields.h).
#include <QtTest>

#include <cmath>
#include <limits>

#include "app/embedded_scene.h"
#include "devices/calibration/manifest_targets.h"
#include "model/analysis/fit_parameters.h"
#include "model/analysis/fit_targets.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"
#include "model/analysis/tolerance_stats.h"
#include "model/color/measurement_csv.h"
#include "model/io/json_fields.h"
#include "model/scene/scene_io.h"
#include "tests/test_files.h"

namespace tst_input_hardening {

using namespace fovea;
using nlohmann::json;

namespace {

using fovea::embeddedDefaultScene;

json spec(const json& patch = json::object()) {
  json j = json::parse(R"({
    "format": "fovea-tolerance",
    "parameters": [
      {"name": "a", "kind": "gaze_tracker", "distribution": "normal", "sigma": 1.0},
      {"name": "b", "path": "eye.relief_mm", "distribution": "uniform", "half_width": 0.5}
    ],
    "gaze": {"from_deg": -10, "to_deg": 10, "step_deg": 10},
    "pass": {"inset_error_deg": {"max": 1.0}},
    "target_yield": 0.9
  })");
  j.merge_patch(patch);
  return j;
}

// The message of the std::invalid_argument `f` throws ("" when it throws none).
template <class F>
QString refusal(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

// A tolerance part of `trials` records, shard 0 of 1, from `spec`, with every record's figures.
json part(const json& spec_json, const std::vector<json>& records) {
  json p{{"format", "fovea-tolerance-part"},
         {"version", 1},
         {"shard", {0, 1}},
         {"scene", "s"},
         {"scene_digest", "0"},
         {"seed", 1},
         {"trials", records.size()},
         {"spec", spec_json},
         {"nominal",
          {{"fov_min_deg", 90},
           {"fov_zero_gaze_deg", 90},
           {"eyebox_mm", 5},
           {"inset_error_deg", 0},
           {"mean_efficiency", 0.5}}}};
  p["records"] = records;
  return p;
}

json record(std::uint64_t trial, json inputs, json figures) {
  return {{"trial", trial}, {"inputs", std::move(inputs)}, {"figures", std::move(figures)}};
}

}  // namespace

class TestInputHardening : public QObject {
  Q_OBJECT
 private slots:
  // Figures that overflowed (a tracker sigma of 1e308) are counted in non_finite and binned
  // nowhere; the histogram of the finite ones spans [-1e308, 1e308] without overflow.
  void statisticsCountNonFiniteFigures() {
    ToleranceSpec s = parseToleranceSpec(spec({{"sensitivity", "none"}}));
    std::vector<ToleranceRecord> records;
    const double nan = std::nan(""), inf = HUGE_VAL;
    const double firsts[] = {nan, inf, -inf, -1e308, 1e308, 0.0};
    for (std::uint64_t i = 0; i < 6; ++i) {
      ToleranceRecord r;
      r.trial = i;
      r.inputs = {firsts[i], 0.1};
      r.figures = {firsts[i], 90, 5, 0.5, 0.5};
      records.push_back(r);
    }
    const json st = toleranceStatistics(s, 1, records);
    const json& fov = st["figures"]["fov_min_deg"];
    QCOMPARE(fov["count"].get<int>(), 3);
    QCOMPARE(fov["non_finite"].get<int>(), 3);
    QCOMPARE(fov["min"].get<double>(), -1e308);
    QCOMPARE(fov["max"].get<double>(), 1e308);
    QCOMPARE(fov["mean"].get<double>(), 0.0);
    const auto counts = fov["histogram"]["counts"].get<std::vector<int>>();
    QCOMPARE(counts.size(), std::size_t(20));
    QCOMPARE(counts.front(), 1);  // -1e308
    QCOMPARE(counts[10], 1);      // 0, the middle
    QCOMPARE(counts.back(), 1);   // 1e308
    const auto edges = fov["histogram"]["edges"].get<std::vector<double>>();
    QCOMPARE(edges.front(), -1e308);
    QCOMPARE(edges.back(), 1e308);
    for (double e : edges) QVERIFY(std::isfinite(e));
    QCOMPARE(st["inputs"]["a"]["non_finite"].get<int>(), 3);
    // Records whose shape differs from the spec's are refused, never read past their end.
    records[2].inputs.clear();
    QVERIFY(refusal([&] { toleranceStatistics(s, 1, records); }).contains("trial 2 has 0 inputs"));
  }

  // The Saltelli design's ranking with NaN indices (outputs that overflowed) keeps a strict
  // weak order: no crash, every parameter ranked once.
  void sensitivityRankingWithNonFiniteOutputs() {
    // Every unit passes (the failure indicator does not vary): the ranking falls back to the
    // smallest FOV, whose values of 1e200 overflow the variance: NaN indices.
    const ToleranceSpec s = parseToleranceSpec(spec({{"pass", {{"inset_error_deg", {{"max", 1e9}}}}}}));
    std::vector<ToleranceRecord> records;
    for (std::uint64_t i = 0; i < 40; ++i) {
      ToleranceRecord r;
      r.trial = i;
      r.inputs = trialInputs(s, 3, i);
      r.figures = {1e200 * r.inputs[0], 90, 5, std::abs(r.inputs[0]), 0.5};
      records.push_back(r);
    }
    const json st = toleranceStatistics(s, 3, records);
    QCOMPARE(st["sensitivity"]["ranked_by"].get<std::string>(), std::string("fov_min_deg"));
    QCOMPARE(st["sensitivity"]["ranking"].size(), std::size_t(2));
  }

  // merge: records with empty or short inputs/figures arrays are refused naming the file and
  // the key; null figures (non-finite values as the JSON printer writes them) are counted.
  void mergeRefusesRecordsOfTheWrongShape() {
    const json sj = spec({{"sensitivity", "none"}});
    const json good = record(0, {0.1, 0.2}, {90, 90, 5, 0.1, 0.5});
    const std::vector<std::string> files{"part-0.json"};
    const json ok = mergeToleranceParts({part(sj, {good, record(1, {0.1, 0.2}, {nullptr, 90, 5, 0.1, 0.5})})}, files);
    QCOMPARE(ok["figures"]["fov_min_deg"]["non_finite"].get<int>(), 1);
    QCOMPARE(ok["figures"]["fov_min_deg"]["count"].get<int>(), 1);
    const QString empty = refusal([&] {
      mergeToleranceParts({part(sj, {good, record(1, json::array(), json::array())})}, files);
    });
    QVERIFY2(empty.contains("merge: part-0.json: records[1].inputs: must be an array of 2 numbers"), qPrintable(empty));
    const QString short_figures = refusal([&] {
      mergeToleranceParts({part(sj, {good, record(1, {0.1, 0.2}, {90, 90})})}, files);
    });
    QVERIFY2(short_figures.contains("records[1].figures: must be an array of 5 numbers") &&
                 short_figures.contains("got 2 elements"),
             qPrintable(short_figures));
    const QString text = refusal([&] {
      mergeToleranceParts({part(sj, {good, record(1, {0.1, "x"}, {90, 90, 5, 0, 0})})}, files);
    });
    QVERIFY2(text.contains("records[1].inputs[1]: must be a number or null, got string"), qPrintable(text));
    json bad_shard = part(sj, {good});
    bad_shard["shard"] = {0, 4294967297.0};
    QVERIFY(refusal([&] { mergeToleranceParts({bad_shard}, files); }).contains("shard: must be [K, N]"));
    json bad_seed = part(sj, {good});
    bad_seed["seed"] = -1;
    QVERIFY(refusal([&] { mergeToleranceParts({bad_seed}, files); }).contains("part-0.json: seed: must be an integer"));
  }

  // The spec's integers are integers in their range, read on the exact JSON value.
  void specIntegersDoNotWrapOrTruncate() {
    const auto opt = [](const char* key, json v) { return spec({{"optimiser", {{key, v}}}}); };
    QVERIFY2(refusal([&] {
               parseToleranceSpec(opt("edge_bisections", 4294967299ULL), "s.json");
             }).contains("s.json: optimiser.edge_bisections: must be an integer in [0, 20], got 4294967299"),
             qPrintable(refusal([&] { parseToleranceSpec(opt("edge_bisections", 4294967299ULL), "s.json"); })));
    QVERIFY(
        refusal([&] { parseToleranceSpec(opt("edge_bisections", 1099511627776ULL)); }).contains("got 1099511627776"));
    QVERIFY(refusal([&] {
              parseToleranceSpec(opt("bracket_points", 9.9));
            }).contains("optimiser.bracket_points: must be an integer in [3, 65], got 9.9"));
    QVERIFY(refusal([&] {
              parseToleranceSpec(opt("bracket_points", 18446744073709551615ULL));
            }).contains("got 18446744073709551615"));
    QCOMPARE(parseToleranceSpec(opt("edge_bisections", 20)).optimiser.edge_bisections, 20);
    // Types: a string where a number belongs is named with its key, never nlohmann's text.
    const QString typed = refusal([&] { parseToleranceSpec(spec({{"target_yield", "high"}}), "s.json"); });
    QCOMPARE(typed, QString("s.json: target_yield: must be a number, got a string"));
    QVERIFY(!typed.contains("json.exception"));
    QVERIFY(refusal([&] { parseToleranceSpec(spec({{"shift", 3}})); }).contains("shift: must be a string"));
  }

  // A key no reader asks for is refused with its path and the keys its entry reads: a typo
  // would otherwise fall back to the default silently and the study answer another question.
  void specUnknownKeysAreRefused() {
    const QString typo = refusal([&] { parseToleranceSpec(spec({{"gaze", {{"from", -20}}}}), "s.json"); });
    QVERIFY2(typo == "s.json: gaze.from: not a field of this entry (it reads axis, from_deg, step_deg, to_deg)",
             qPrintable(typo));
    json unused = spec();
    unused["parameters"][0]["half_width"] = 2.0;  // a normal distribution reads sigma
    const QString mode = refusal([&] { parseToleranceSpec(unused, "s.json"); });
    QVERIFY2(mode.startsWith("s.json: parameters[0].half_width: not a field of this entry (it reads "),
             qPrintable(mode));
    QVERIFY(mode.contains("sigma"));
    QVERIFY(refusal([&] {
              parseToleranceSpec(spec({{"pass", {{"inset_error_deg", {{"maximum", 1.0}}}}}}));
            }).contains("pass.inset_error_deg.maximum: not a field of this entry (it reads max, min)"));
    QVERIFY(refusal([&] { parseToleranceSpec(spec({{"target_yeild", 0.5}})); }).contains("target_yeild: not a field"));
    // The shipped spec, with its free-text "notes" and "version", reads.
    const json shipped = json::parse(
        fovea::testing::readFileText(std::string(FOVEA_SOURCE_DIR) + "/resources/tolerance/prototype-tolerance.json"));
    QCOMPARE(parseToleranceSpec(shipped, "prototype-tolerance.json").parameters.size(), shipped["parameters"].size());
  }

  // Gazes within +-80 deg; the list is built by count, so from = to = 1e300 or a step of
  // 5e-324 can no longer grow it forever.
  void specGazesAreBounded() {
    const auto gaze = [](json g) { return spec({{"gaze", std::move(g)}}); };
    QVERIFY(refusal([&] {
              parseToleranceSpec(gaze({{"from_deg", 1e300}, {"to_deg", 1e300}}));
            }).contains("gaze.from_deg: must be in [-80, 80], got 1e+300"));
    QVERIFY(refusal([&] { parseToleranceSpec(gaze({{"from_deg", -85}})); }).contains("gaze.from_deg"));
    QVERIFY(refusal([&] { parseToleranceSpec(gaze({{"step_deg", 5e-324}})); }).contains("at most 200 steps"));
    const ToleranceSpec one = parseToleranceSpec(gaze({{"from_deg", 5}, {"to_deg", 5}, {"step_deg", 5e-324}}));
    QCOMPARE(one.gazes_deg, std::vector<double>{5.0});
    const ToleranceSpec three = parseToleranceSpec(spec());
    QCOMPARE(three.gazes_deg, (std::vector<double>{-10, 0, 10}));
    // The sweep's own list: bounded by the CLI's cap the same way.
    QCOMPARE(sweepGazes(7, 7, 1e-300).size(), std::size_t(1));
    QVERIFY(refusal([] { sweepGazes(-80, 80, 1e-300); }).contains("more than 2000 gaze samples"));
    QCOMPARE(sweepGazes(-10, 10, 5).size(), std::size_t(5));
  }

  // An integer field of the scene cannot take a tolerance's offset.
  void specPathsAreRealNumbersOfTheScene() {
    json j = spec();
    j["parameters"][1]["path"] = "projector.pixels[0]";
    const ToleranceSpec s = parseToleranceSpec(j, "s.json");
    const QString m = refusal([&] { checkToleranceSpecPaths(s, embeddedDefaultScene(), "s.json"); });
    QVERIFY2(m.contains("s.json: parameters[1].path: \"projector.pixels[0]\" is an integer field"), qPrintable(m));
    j["parameters"][1]["path"] = "eye.nose_mm";
    QVERIFY(refusal([&] {
              checkToleranceSpecPaths(parseToleranceSpec(j), embeddedDefaultScene(), "s.json");
            }).contains("s.json: parameters[1].path:"));
    QVERIFY(refusal([&] { checkToleranceSpecPaths(parseToleranceSpec(spec()), embeddedDefaultScene()); }).isEmpty());
  }

  // Fit targets: sigma and value in ranges that keep chi2 finite; the eye-box sweep's gazes and a
  // target's wavelength in range.
  void fitTargetRanges() {
    const auto target = [](json patch) {
      json t{{"id", "t"}, {"observable", "fov_deg"}, {"value", 90.0}, {"sigma", 0.5}};
      t.merge_patch(patch);
      return json::array({t});
    };
    QVERIFY(refusal([&] { parseFitTargets(target({{"sigma", 5e-324}})); }).contains("targets[0].sigma: must be in ["));
    QVERIFY(refusal([&] { parseFitTargets(target({{"value", 1e308}})); }).contains("targets[0].value: must be in ["));
    QVERIFY(refusal([&] { parseFitTargets(target({{"value", -1e308}})); }).contains("targets[0].value"));
    const json eff{{"observable", "mean_efficiency"}, {"value", 0.5}};
    auto wavelength = [&](double nm) {
      json t = target(eff);
      t[0]["wavelength_nm"] = nm;
      return refusal([&] { parseFitTargets(t); });
    };
    QVERIFY2(wavelength(0).contains("wavelength_nm: must be > 0, got 0"), qPrintable(wavelength(0)));
    QVERIFY2(wavelength(-5).contains("wavelength_nm: must be > 0"), qPrintable(wavelength(-5)));
    QVERIFY2(wavelength(2001).contains("wavelength_nm: must be <= 2000, got 2001"), qPrintable(wavelength(2001)));
    QVERIFY(wavelength(532).isEmpty());
    const json eyebox{{"id", "e"}, {"observable", "eyebox_mm"}, {"value", 5.0}, {"sigma", 0.5}, {"gaze_from", -1e6}};
    QVERIFY(refusal([&] { parseFitTargets(json::array({eyebox})); }).contains("gaze_from: must lie in [-80, 80] deg"));
    json eyebox_to = eyebox;
    eyebox_to.erase("gaze_from");
    eyebox_to["gaze_to"] = 1e6;
    QVERIFY(refusal([&] { parseFitTargets(json::array({eyebox_to})); }).contains("gaze_to: must lie in [-80, 80] deg"));
  }

  // A step captured twice gives one target (its last capture), so `fit` reads the file back.
  void manifestStepCapturedTwice() {
    const json step{{"id", "g10"},         {"kind", "geometric"},      {"display", "peripheral"},
                    {"gaze_deg", {10, 0}}, {"targets", json::array()}, {"pattern", {{"kind", "off"}}}};
    json m{{"format", "fovea-capture-session"}, {"kind", "geometric"}, {"steps", {step}}};
    m["captures"] = {{{"step", "g10"}, {"positions", {{"hoe.x", 1.5}}}},
                     {{"step", "g10"}, {"positions", {{"hoe.x", 1.75}}}}};
    devices::ManifestTargets t;
    try {
      t = devices::fitTargetsFromManifest(m, {0.05, "bench"});
    } catch (const std::exception& e) {
      QFAIL(e.what());
    }
    QCOMPARE(t.targets.size(), std::size_t(1));
    QCOMPARE(t.targets[0].value, 1.75);
    QCOMPARE(parseFitTargets(fitTargetsJson(t.targets)).size(), std::size_t(1));
    QVERIFY(!t.skipped.empty() && QString::fromStdString(t.skipped.back()).contains("captured again"));
    // Two steps of one id: a capture of "g10" could be either gaze (+10 or -10): refused.
    json twice = m;
    json other = step;
    other["gaze_deg"] = {-10, 0};
    twice["steps"].push_back(other);
    QVERIFY2(refusal([&] {
               devices::fitTargetsFromManifest(twice, {0.05, "bench"});
             }).contains("steps[1].id: \"g10\" is also the id of steps[0]"),
             qPrintable(refusal([&] {
               devices::fitTargetsFromManifest(twice, {0.05, "bench"});
             })));
    m["captures"][0] = 7;
    QVERIFY(refusal([&] {
              devices::fitTargetsFromManifest(m, {0.05, "bench"});
            }).contains("captures[0]: must be an object, got a number"));
    m["steps"][0]["gaze_deg"] = "x";
    QVERIFY(refusal([&] {
              devices::fitTargetsFromManifest(m, {0.05, "bench"});
            }).contains("steps[0].gaze_deg: must be an array of 2 numbers"));
  }

  // The colour CSV: "X" (tristimulus) is not "x"; a UTF-8 BOM is accepted; a channel without
  // light is a problem.
  void colourCsvHeaderAndLuminance() {
    auto csv = [](const std::string& header, double scale) {
      std::string t = header + "\n";
      for (const char* d : {"foveal", "peripheral"})
        for (const char* c : {"R", "G", "B"})
          for (int l = 0; l < 256; ++l) {
            const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
            const int ci = c[0] == 'R' ? 0 : c[0] == 'G' ? 1 : 2;
            t += std::string(d) + "," + c + "," + std::to_string(l) + "," + std::to_string(xy[ci][0]) + "," +
                 std::to_string(xy[ci][1]) + "," + std::to_string(scale * l) + ",1\n";
          }
      return t;
    };
    const auto good = color::importSpectroradiometerCsv(csv("display,channel,level,x,y,Y,repeat", 0.25));
    QVERIFY(good.ok());
    QCOMPARE(good.rows, 1536);
    const auto bom =
        color::importSpectroradiometerCsv("\xEF\xBB\xBF" + csv("display,channel,level,x,y,Y,repeat", 0.25));
    QVERIFY2(bom.ok(), bom.problems.empty() ? "" : bom.problems[0].message.c_str());
    const auto tristimulus = color::importSpectroradiometerCsv(csv("display,channel,level,X,y,Y,repeat", 0.25));
    QVERIFY(!tristimulus.ok());
    // X without Z: named, not read as x.
    QVERIFY2(QString::fromStdString(tristimulus.problems[0].message)
                 .contains("the header has the tristimulus column(s) X but lacks Z"),
             tristimulus.problems[0].message.c_str());
    QVERIFY(QString::fromStdString(tristimulus.problems[0].message).contains("X is not the chromaticity x"));
    const auto dark = color::importSpectroradiometerCsv(csv("display,channel,level,x,y,Y,repeat", 0.0));
    QVERIFY(!dark.ok());
    QVERIFY(QString::fromStdString(dark.problems[0].message).contains("does not rise"));
    // Garbage stops at 1000 problems instead of collecting one per line.
    std::string garbage = "display,channel,level,x,y,Y,repeat\n";
    for (int i = 0; i < 5000; ++i) garbage += "a\n";
    QCOMPARE(color::importSpectroradiometerCsv(garbage).problems.size(), std::size_t(1001));
  }

  // --free PATH=+-D: the window is clipped to the field's open range first, then kept 1e-9 of
  // the clipped window inside it (the margin of the unclipped window refused the scene's value),
  // at most 1e-6 of the way from the scene's value to the bound (the clipped window of a large D
  // still kept the search above half the scene's value).
  void freeWindowClippedBeforeTheMargin() {
    const Scene s = embeddedDefaultScene();
    std::vector<FreeParameter> p;
    try {
      p = parseFreeParameters(s, {"eye.relief_mm=+-1e12"});
    } catch (const std::exception& e) {
      QFAIL(e.what());
    }
    QCOMPARE(p.size(), std::size_t(1));
    QVERIFY(p[0].lower > 0);             // the open bound "> 0" kept
    QVERIFY(p[0].lower < p[0].initial);  // the scene's value inside
    QVERIFY(p[0].upper >= p[0].initial + 1e11);
    // The whole open range below the value is searched: (0, 22] less 1e-6 of 22 mm (was 11 mm).
    QCOMPARE(p[0].initial, 22.0);
    QVERIFY2(std::abs(p[0].lower - 22e-6) < 1e-12, qPrintable(QString::number(p[0].lower, 'g', 17)));
    // A window inside the range keeps its own bounds; a small one reaching the bound keeps
    // 1e-9 of itself: relief +-22 mm is (0, 44] less 44e-9 mm.
    const FreeParameter inside = parseFreeParameter(s, "eye.relief_mm=+-21");
    QCOMPARE(inside.lower, 1.0);
    const FreeParameter reach = parseFreeParameter(s, "eye.relief_mm=+-22");
    QVERIFY2(std::abs(reach.lower - 44e-9) < 1e-15, qPrintable(QString::number(reach.lower, 'g', 17)));
  }

  // The field reader's own rules.
  void jsonFieldReader() {
    const json j = json::parse(R"({"n": 4294967299, "f": 2.5, "s": "x", "neg": -3, "big": 1e23, "o": {"k": true}})");
    const JsonFields f(j, "in.json");
    QCOMPARE(f.integer("neg", -5, 5), -3LL);
    QVERIFY(
        refusal([&] { f.integer("n", 0, 20); }).contains("in.json: n: must be an integer in [0, 20], got 4294967299"));
    QVERIFY(refusal([&] { f.integer("f", 0, 20); }).contains("got 2.5"));
    QVERIFY(refusal([&] { f.unsignedInteger("neg"); }).contains("got -3"));
    QVERIFY(refusal([&] { f.unsignedInteger("big"); }).contains("got 1e+23"));
    QCOMPARE(f.unsignedInteger("n"), std::uint64_t(4294967299ULL));
    QVERIFY(refusal([&] { f.number("missing", Range::any()); }).contains("in.json: missing: missing required field"));
    QCOMPARE(f.number("missing", Range::any(), 7.0), 7.0);
    QVERIFY(refusal([&] { f.text("s", {"a", "b"}); }).contains("must be one of a, b, got \"x\""));
    QCOMPARE(f.object("o")->boolean("k"), true);
    QVERIFY(refusal([&] {
              f.object("o")->number("k", Range::any());
            }).contains("in.json: o.k: must be a number, got true"));
  }
};

QTEST_GUILESS_MAIN(TestInputHardening)

}  // namespace tst_input_hardening
#include "tst_input_hardening.moc"
