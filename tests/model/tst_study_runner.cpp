// The study runner: determinism across thread counts, prompt cancellation without a
// partial result, progress reporting, and the scene-content result cache.
#include <QtTest>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "app/embedded_scene.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/study_runner.h"
#include "model/scene/scene_io.h"

namespace tst_study_runner {

using namespace fovea;

namespace {
using fovea::embeddedDefaultScene;

// A deterministic, moderately expensive per-sample computation with rounding-sensitive
// floating-point sums (any shared accumulator across threads would change the bits).
double sampleValue(std::size_t i) {
  double s = 0;
  for (int k = 1; k < 20000; ++k) s += std::sin(0.001 * k * (i + 1)) / k;
  return s;
}
}  // namespace

class TestStudyRunner : public QObject {
  Q_OBJECT
 private slots:
  void identicalWhateverTheThreadCount() {
    auto run = [](int threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      return runSamples<double>(64, sampleValue, {});
    };
    const auto one = run(1), many = run(4);
    QVERIFY(one.ok() && many.ok());
    QCOMPARE(one.value->size(), std::size_t{64});
    for (std::size_t i = 0; i < 64; ++i) {
      QCOMPARE(std::memcmp(&(*one.value)[i], &(*many.value)[i], sizeof(double)), 0);
      QCOMPARE((*one.value)[i], sampleValue(i));  // each sample in its own slot, in order
    }
  }

  void lensOptimisationIdenticalAcrossThreadCounts() {
    const Scene scene = embeddedDefaultScene();
    auto catalog = defaultLensCatalog();
    catalog.resize(4);
    LensOptimizationOptions opt;
    opt.starts_per_lens = 2;
    opt.max_evaluations = 60;
    auto run = [&](int threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      return optimizeBeamShapingLens(scene, catalog, opt);
    };
    const auto a = run(1), b = run(3);
    QVERIFY(a.ok() && b.ok());
    QCOMPARE(a.value->rms_after_um, b.value->rms_after_um);
    for (std::size_t i = 0; i < a.value->candidates.size(); ++i) {
      QCOMPARE(a.value->candidates[i].placement.distance_mm, b.value->candidates[i].placement.distance_mm);
      QCOMPARE(a.value->candidates[i].placement.tilt_deg, b.value->candidates[i].placement.tilt_deg);
    }
  }

  void cancellationIsPromptAndReportsNothing() {
    // Cancelled from inside the 5th sample, no clock involved: a sample starts only after its
    // check of the flag, so once it is set at most one more sample per worker thread can
    // start (one that had already passed its check), and the study reports nothing.
    std::atomic<bool> cancel{false};
    std::atomic<int> started{0};
    StudyControl control;
    control.cancel = &cancel;
    auto compute = [&](std::size_t) {
      if (++started == 5) cancel = true;
      return 1.0;
    };
    const auto r = runSamples<double>(1000, compute, control);
    QCOMPARE(r.status, StudyStatus::Cancelled);
    QVERIFY(!r.value.has_value());
    const int workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    QVERIFY2(started >= 5 && started <= 5 + workers, qPrintable(QString::number(started.load())));
  }

  void cancelledBeforeStartComputesNothing() {
    std::atomic<bool> cancel{true};
    std::atomic<int> calls{0};
    StudyControl control;
    control.cancel = &cancel;
    const auto r = runSamples<int>(
        10, [&](std::size_t) { return ++calls; }, control);
    QVERIFY(!r.ok());
    QCOMPARE(calls.load(), 0);
  }

  void cancelledLensOptimisationHasNoResult() {
    std::atomic<bool> cancel{true};
    StudyControl control;
    control.cancel = &cancel;
    const auto r = optimizeBeamShapingLens(embeddedDefaultScene(), defaultLensCatalog(), {}, control);
    QCOMPARE(r.status, StudyStatus::Cancelled);
    QVERIFY(!r.value.has_value());
  }

  void progressIsMonotonicAndEndsAtOne() {
    std::vector<double> seen;
    StudyControl control;
    control.on_progress = [&](double f) { seen.push_back(f); };
    const auto r = runSamples<double>(40, sampleValue, control);
    QVERIFY(r.ok());
    QCOMPARE(seen.size(), std::size_t{40});
    for (std::size_t i = 1; i < seen.size(); ++i) QVERIFY(seen[i] >= seen[i - 1]);
    QCOMPARE(seen.back(), 1.0);
  }

  void cacheKeysOnSceneContent() {
    StudyCache cache;
    const Scene scene = embeddedDefaultScene();
    const nlohmann::json params{{"from", -20}, {"to", 20}};
    const std::string key = StudyCache::makeKey("sweep", params, serializeScene(scene));
    QVERIFY(!cache.find(key));
    cache.store(key, nlohmann::json{{"answer", 42}});
    QCOMPARE(cache.find(StudyCache::makeKey("sweep", params, serializeScene(scene)))->at("answer").get<int>(), 42);
    Scene moved = scene;
    moved.eye.relief_mm += 0.5;
    QVERIFY(!cache.find(StudyCache::makeKey("sweep", params, serializeScene(moved))));
    QVERIFY(
        !cache.find(StudyCache::makeKey("sweep", nlohmann::json{{"from", -10}, {"to", 20}}, serializeScene(scene))));
    QCOMPARE(cache.hits(), std::size_t{1});
  }

  void diskCacheSurvivesAcrossInstances() {
    const std::string dir = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp").toStdString() + "/study_cache";
    std::filesystem::remove_all(dir);
    const std::string key = StudyCache::makeKey("x", nlohmann::json::object(), "scene text");
    {
      StudyCache a;
      a.setDirectory(dir);
      a.store(key, nlohmann::json{{"v", 1.5}});
    }
    StudyCache b;
    b.setDirectory(dir);
    const auto got = b.find(key);
    QVERIFY(got.has_value());
    QCOMPARE(got->at("v").get<double>(), 1.5);
    QVERIFY(!b.find(StudyCache::makeKey("x", nlohmann::json::object(), "other scene")));
  }
};

QTEST_GUILESS_MAIN(TestStudyRunner)

}  // namespace tst_study_runner
#include "tst_study_runner.moc"
