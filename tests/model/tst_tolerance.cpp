// Tolerancing (model/analysis/tolerance_*.h): the distributions' quantiles, counter-based
// draws and the Saltelli design, the Sobol estimators on a model with known indices, the
// reweighted inverse against its closed form, shards merged equal to one run, and a traced
// trial of the prototype.
#include <QtTest>

#include <cmath>

#include "app/embedded_scene.h"
#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"
#include "model/analysis/tolerance_stats.h"
#include "model/analysis/tolerance_trial.h"
#include "model/scene/scene_io.h"

namespace tst_tolerance {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;

nlohmann::json specJson() {
  return nlohmann::json::parse(R"({
    "format": "fovea-tolerance",
    "parameters": [
      {"name": "a", "kind": "gaze_tracker", "distribution": "normal", "sigma": 1.0},
      {"name": "b", "path": "eye.relief_mm", "distribution": "uniform", "half_width": 0.5},
      {"name": "c", "kind": "laser_temperature", "drift_nm_per_K": 0.1, "distribution": "truncated_normal",
       "sigma": 2.0, "limit": 1.0}
    ],
    "gaze": {"from_deg": -10, "to_deg": 10, "step_deg": 10},
    "pass": {"inset_error_deg": {"max": 1.0}},
    "target_yield": 0.9
  })");
}

// Synthetic records: figure inset_error_deg = |a|, the others a linear model of the inputs.
std::vector<ToleranceRecord> syntheticRecords(const ToleranceSpec& spec, std::uint64_t seed, std::uint64_t n) {
  std::vector<ToleranceRecord> out;
  for (std::uint64_t i = 0; i < n; ++i) {
    ToleranceRecord r;
    r.trial = i;
    r.inputs = trialInputs(spec, seed, i);
    r.figures = {2.0 * r.inputs[0] + r.inputs[1], 90.0, 5.0, std::abs(r.inputs[0]), 0.5 + 0.1 * r.inputs[2]};
    out.push_back(r);
  }
  return out;
}
}  // namespace

class TestTolerance : public QObject {
  Q_OBJECT
 private slots:
  // Wilson 1927: centre (p + z²/2n)/(1 + z²/n), half-width z/(1 + z²/n) sqrt(p(1-p)/n + z²/4n²).
  void wilsonScoreInterval() {
    const auto a = wilsonInterval(0.5, 100);  // symmetric: 0.5 -+ 0.096170
    QVERIFY(std::abs(a[0] - 0.403830) < 1e-5 && std::abs(a[1] - 0.596170) < 1e-5);
    const auto b = wilsonInterval(0.0, 10);  // no success: [0, 0.27754], not the empty p -+ z SE
    QCOMPARE(b[0], 0.0);
    QVERIFY(std::abs(b[1] - 0.277540) < 1e-5);
    const auto c = wilsonInterval(1.0, 10);  // mirror image
    QVERIFY(std::abs(c[0] - (1 - 0.277540)) < 1e-5 && c[1] == 1.0);
    const auto d = wilsonInterval(0.3, 0);
    QVERIFY(d[0] == 0.0 && d[1] == 1.0);
    // docs/tolerancing.md: 82 of 100 passing over 12 independent samples (k = 14, 100 trials:
    // 6 Saltelli blocks) is 53.8 - 94.7 %; over 100 independent units it would be 73.3 - 88.3 %.
    const auto e = wilsonInterval(0.82, 12);
    QVERIFY(std::abs(e[0] - 0.538) < 5e-4 && std::abs(e[1] - 0.947) < 5e-4);
    const auto f = wilsonInterval(0.82, 100);
    QVERIFY(std::abs(f[0] - 0.733) < 5e-4 && std::abs(f[1] - 0.883) < 5e-4);
  }

  // What the interval rests on, in words, beside the number (yield.interval_basis); the inverse
  // rows that do not reach the target say how far the scan got.
  void intervalBasisAndUnreachedRows() {
    const ToleranceSpec s = parseToleranceSpec(specJson());
    QVERIFY(s.sobol);
    const std::size_t k = s.parameters.size();
    const auto records = syntheticRecords(s, 2, 6 * (k + 2) + 1);  // 6 whole blocks and one trial more
    const nlohmann::json st = toleranceStatistics(s, 2, records);
    QCOMPARE(st["yield"]["independent_samples"].get<double>(), 12.0);
    QCOMPARE(st["yield"]["interval_basis"].get<std::string>(),
             std::string("12 independent samples: the A and B rows of the Saltelli design's 6 blocks (its A_B rows "
                         "repeat their values)"));
    nlohmann::json j = specJson();
    j["sensitivity"] = "none";
    const ToleranceSpec plain = parseToleranceSpec(j);
    const nlohmann::json sp = toleranceStatistics(plain, 2, syntheticRecords(plain, 2, 500));
    QCOMPARE(sp["yield"]["interval_basis"].get<std::string>(),
             std::string("500 independent samples (plain Monte Carlo)"));
    const auto& b = sp["inverse"]["parameters"][1];  // does not decide the pass
    QVERIFY(!b["achievable"].get<bool>());
    QVERIFY2(b.contains("stopped_by") && b.contains("best_yield") && b.contains("smallest_scale"), b.dump().c_str());
    QVERIFY(b["best_yield"].get<double>() < plain.target_yield);
    QVERIFY(b["smallest_scale"].get<double>() <= b["best_scale"].get<double>() + 1e-12);
  }

  void quantilesAndDraws() {
    const ToleranceSpec s = parseToleranceSpec(specJson());
    const ToleranceParameter& n = s.parameters[0];
    QVERIFY(std::abs(n.quantile(0.975) - 1.959963984540054) < 1e-12);
    QVERIFY(std::abs(n.quantile(0.5)) < 1e-15);
    QVERIFY(std::abs(n.quantile(1e-6) + 4.753424308822899) < 1e-9);
    QCOMPARE(s.parameters[1].quantile(0.75), 0.25);
    const ToleranceParameter& t = s.parameters[2];
    QVERIFY(std::abs(t.quantile(1e-12)) <= 1.0 + 1e-9 && std::abs(t.quantile(1 - 1e-12)) <= 1.0 + 1e-9);
    QVERIFY(std::abs(t.quantile(0.5)) < 1e-12);
    // Counter-based: the same (seed, trial, stream, parameter) gives the same number.
    QCOMPARE(counterUniform(7, 123, 0, 2), counterUniform(7, 123, 0, 2));
    QVERIFY(counterUniform(7, 123, 0, 2) != counterUniform(8, 123, 0, 2));
    double sum = 0;
    for (int i = 0; i < 20000; ++i) {
      const double u = counterUniform(3, i, 0, 0);
      QVERIFY(u > 0 && u < 1);
      sum += u;
    }
    QVERIFY(std::abs(sum / 20000 - 0.5) < 0.01);
    // Saltelli design: block of k + 2 = 5 trials: A, B, A_B^(0), A_B^(1), A_B^(2).
    const auto a = trialInputs(s, 5, 10), b = trialInputs(s, 5, 11), ab1 = trialInputs(s, 5, 13);
    QVERIFY(a[0] != b[0] && a[1] != b[1]);
    QCOMPARE(ab1[0], a[0]);
    QCOMPARE(ab1[1], b[1]);
    QCOMPARE(ab1[2], a[2]);
  }

  void specErrorsNameTheKey() {
    nlohmann::json j = specJson();
    j["parameters"][1]["distribution"] = "lognormal";
    try {
      parseToleranceSpec(j);
      QFAIL("accepted an unknown distribution");
    } catch (const std::invalid_argument& e) {
      QVERIFY(QString(e.what()).contains("parameters[1]") && QString(e.what()).contains("lognormal"));
    }
    j = specJson();
    j["parameters"][0]["sigma"] = -1;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseToleranceSpec(j));
    j = specJson();
    j["pass"] = {{"fov_max", {{"min", 1}}}};
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseToleranceSpec(j));
  }

  void sobolIndicesOfALinearModel() {
    // Y = 3 x1 + x2 + 0 x3 with independent standard normals: S1 = ST1 = 0.9, S2 = ST2 = 0.1, S3 = 0.
    const std::size_t m = 4000;
    std::vector<double> fa(m), fb(m);
    std::vector<std::vector<double>> ab(3, std::vector<double>(m));
    ToleranceParameter n;
    n.sigma = 1;
    auto f = [](double x1, double x2, double) { return 3 * x1 + x2; };
    for (std::size_t j = 0; j < m; ++j) {
      double xa[3], xb[3];
      for (int p = 0; p < 3; ++p)
        xa[p] = n.quantile(counterUniform(11, j, 0, p)), xb[p] = n.quantile(counterUniform(11, j, 1, p));
      fa[j] = f(xa[0], xa[1], xa[2]);
      fb[j] = f(xb[0], xb[1], xb[2]);
      for (int p = 0; p < 3; ++p) {
        double x[3] = {xa[0], xa[1], xa[2]};
        x[p] = xb[p];
        ab[p][j] = f(x[0], x[1], x[2]);
      }
    }
    const std::vector<SobolIndex> s = sobolIndices(fa, fb, ab, 100, 1);
    QCOMPARE(s.size(), std::size_t{3});
    const double expect[3] = {0.9, 0.1, 0.0};
    for (int p = 0; p < 3; ++p) {
      QVERIFY2(std::abs(s[p].first - expect[p]) < 4 * s[p].first_se + 1e-12,
               qPrintable(QString("S%1 %2 +- %3").arg(p).arg(s[p].first).arg(s[p].first_se)));
      QVERIFY(std::abs(s[p].total - expect[p]) < 4 * s[p].total_se + 1e-12);
      QVERIFY(s[p].first_se < 0.05);
    }
    QVERIFY(s[0].first_se > 0);
  }

  void inverseMeetsTheClosedForm() {
    // Pass iff |a| <= 1, a ~ N(0, 1): yield 68.3 %; 90 % needs sigma = 1 / 1.6449 (c = 0.608).
    nlohmann::json j = specJson();
    j["sensitivity"] = "none";
    const ToleranceSpec s = parseToleranceSpec(j);
    const auto records = syntheticRecords(s, 2, 6000);
    const nlohmann::json st = toleranceStatistics(s, 2, records);
    QVERIFY(std::abs(st["yield"]["value"].get<double>() - 0.6827) < 3 * st["yield"]["standard_error"].get<double>());
    const auto& a = st["inverse"]["parameters"][0];
    QCOMPARE(a["parameter"].get<std::string>(), std::string("a"));
    QVERIFY(a["achievable"].get<bool>());
    QVERIFY2(std::abs(a["scale"].get<double>() - 1.0 / 1.6448536) < 0.03, a.dump().c_str());
    // Parameters that do not decide the pass cannot reach 90 % alone.
    QVERIFY(!st["inverse"]["parameters"][1]["achievable"].get<bool>());
  }

  void shardsMergeToTheUnshardedResult() {
    const ToleranceSpec s = parseToleranceSpec(specJson());
    ToleranceRunInfo info{"synthetic", "0123", 9, 23, {1, 2, 3, 4, 5}};
    const auto all = syntheticRecords(s, 9, 23);
    const std::string whole = toleranceResultJson(s, info, all).dump();
    std::vector<nlohmann::json> parts;
    for (const int k : {2, 0, 1}) {  // any order
      const TrialRange r = shardRange(23, k, 3);
      const std::vector<ToleranceRecord> slice(all.begin() + r.begin, all.begin() + r.end);
      // Through text, as the files carry them.
      parts.push_back(nlohmann::json::parse(tolerancePartJson(s, info, k, 3, slice).dump()));
    }
    QCOMPARE(mergeToleranceParts(parts).dump(), whole);
    parts.erase(parts.begin());  // shard 2 missing
    try {
      mergeToleranceParts(parts);
      QFAIL("merged with a shard missing");
    } catch (const std::invalid_argument& e) {
      QVERIFY2(QString(e.what()).contains("missing shard(s) 2 of 3"), e.what());
    }
    QCOMPARE(shardRange(10, 0, 3).end, std::uint64_t{3});
    QCOMPARE(shardRange(10, 2, 3).end, std::uint64_t{10});
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, shardRange(10, 3, 3));
  }

  void tracedTrialOfThePrototype() {
    nlohmann::json j = specJson();
    j["wavelength_nm"] = 532;
    j["compensator"] = "fixed";
    const ToleranceSpec s = parseToleranceSpec(j);
    const Scene scene = embeddedDefaultScene();
    // Laser drift: 0.1 nm/K x dT on every laser; the traced laser keeps its drifted wavelength.
    const Scene warm = perturbedScene(scene, s, {0.0, 0.3, 1.0});
    QCOMPARE(warm.projector.wavelengths_nm.size(), std::size_t{1});
    QVERIFY(std::abs(warm.projector.wavelengths_nm[0] - 532.1) < 1e-9);
    QVERIFY(std::abs(warm.eye.relief_mm - 22.3) < 1e-12);
    const std::vector<double> nominal = nominalFigures(scene, s);
    QCOMPARE(nominal.size(), toleranceFigureNames().size());
    // At zero gaze the Maxwellian field at 532 nm ends at the plate: 2 atan(22 / 22) = 90 deg.
    QVERIFY2(std::abs(nominal[1] - 90.0) < 0.05, qPrintable(QString::number(nominal[1])));
    QVERIFY(nominal[0] <= nominal[1] && nominal[0] > 60);
    QVERIFY(nominal[2] > 0);
    QCOMPARE(nominal[3], 0.0);
    // A tracker error of 2 deg lands the inset 2 deg off and costs FOV with the fixed table.
    const FovEvaluator eval = toleranceEvaluator(s);
    const CompensationTable table = nominalCompensation(scene, s, eval);
    const std::vector<double> off = runToleranceTrial(scene, s, eval, {2.0, 0.0, 0.0}, table);
    QCOMPARE(off[3], 2.0);
    QVERIFY(off[0] <= nominal[0] + 0.05);
  }
};

QTEST_APPLESS_MAIN(TestTolerance)

}  // namespace tst_tolerance
#include "tst_tolerance.moc"
