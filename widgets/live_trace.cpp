#include "widgets/live_trace.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QTimer>

#include <mutex>
#include <stdexcept>

#include "model/analysis/gaze_studies.h"
#include "model/analysis/trace_evaluator.h"
#include "model/physics/projector_rays.h"

namespace fovea::widgets {

namespace {
struct Superseded {};
}  // namespace

// Results of the expensive stages of the last jobs, reused by the next ones. Touched by
// one job at a time (the pool has one thread), guarded anyway.
struct LiveTrace::Cache {
  std::mutex mutex;
  // diffractScene() depends on everything but the gaze.
  std::optional<Scene> diffraction_scene;
  std::array<double, 2> diffraction_shift{0, 0};
  int diffraction_rays = 0;
  std::shared_ptr<const std::vector<TracedRay>> diffraction;
  // x_p for one (scene without gaze, gaze).
  std::optional<Scene> shift_scene;
  std::array<double, 2> shift_gaze{0, 0};
  int shift_rays = 0;
  std::array<double, 2> shift{0, 0};
};

LiveTrace::LiveTrace(QObject* parent)
    : QObject(parent), cache_(std::make_shared<Cache>()), newest_(std::make_shared<std::atomic<quint64>>(0)) {
  qRegisterMetaType<std::shared_ptr<const LiveTraceResult>>();
  pool_.setMaxThreadCount(1);  // the trace itself is parallel (TBB)
}

LiveTrace::~LiveTrace() {
  newest_->store(~quint64{0});  // every running job is stale now
  pool_.waitForDone();
}

void LiveTrace::request(const Scene& scene, const LiveTraceSettings& settings) {
  ++requests_;
  settings_ = settings;
  const bool wasBusy = isBusy();
  pending_ = Job{++generation_, scene, settings};
  newest_->store(generation_);
  if (!wasBusy) emit busyChanged(true);
  if (!running_ && !startQueued_) {
    startQueued_ = true;
    QTimer::singleShot(0, this, [this] {
      startQueued_ = false;
      startPending();
    });
  }
}

void LiveTrace::startPending() {
  if (running_ || !pending_) return;
  Job job = std::move(*pending_);
  pending_.reset();
  running_ = true;
  ++started_;
  std::shared_ptr<Cache> cache = cache_;
  std::shared_ptr<std::atomic<quint64>> newest = newest_;
  pool_.start([this, job = std::move(job), cache, newest] {
    std::shared_ptr<LiveTraceResult> result = run(job, *cache, *newest);
    QMetaObject::invokeMethod(
        this, [this, result] { jobFinished(result); }, Qt::QueuedConnection);
  });
}

void LiveTrace::jobFinished(std::shared_ptr<LiveTraceResult> result) {
  running_ = false;
  if (result && result->generation == generation_) {
    latest_ = result;
    ++delivered_;
    emit resultReady(latest_);
  } else {
    ++dropped_;
  }
  if (pending_)
    startPending();
  else
    emit busyChanged(false);
}

bool LiveTrace::waitForIdle(int timeout_ms) {
  QElapsedTimer t;
  t.start();
  while (isBusy() || startQueued_) {
    if (t.elapsed() > timeout_ms) return false;
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  }
  return latest_ && latest_->generation == generation_;
}

std::shared_ptr<LiveTraceResult> LiveTrace::run(const Job& job, Cache& cache, const std::atomic<quint64>& newest) {
  QElapsedTimer timer;
  timer.start();
  auto stale = [&] { return newest.load() != job.generation; };
  auto result = std::make_shared<LiveTraceResult>();
  result->generation = job.generation;
  result->scene = job.scene;
  result->settings = job.settings;
  try {
    Scene base = job.scene;  // everything the diffraction depends on
    base.eye.gaze_deg = {0.0, 0.0};
    const auto gaze = job.scene.eye.gaze_deg;
    std::array<double, 2> shift{0.0, 0.0};
    if (job.settings.follow_gaze && (gaze[0] != 0.0 || gaze[1] != 0.0)) {
      bool cached = false;
      {
        std::lock_guard lock(cache.mutex);
        if (cache.shift_scene && *cache.shift_scene == base && cache.shift_gaze == gaze &&
            cache.shift_rays == job.settings.search_rays) {
          shift = cache.shift;
          cached = true;
        }
      }
      if (!cached) {
        TraceEvaluatorOptions eo;
        eo.rays = job.settings.search_rays;
        const FovEvaluator inner = traceEvaluator(eo);
        const FovEvaluator eval = [&](const Scene& s, const FovQuery& q) {
          if (stale()) throw Superseded{};
          return inner(s, q);
        };
        if (gaze[0] != 0.0)
          shift[0] = optimiseShift(job.scene, eval, gaze[0], GazeAxis::Yaw, ShiftMethod::Hoe).shift_mm;
        if (gaze[1] != 0.0)
          shift[1] = optimiseShift(job.scene, eval, gaze[1], GazeAxis::Pitch, ShiftMethod::Hoe).shift_mm;
        std::lock_guard lock(cache.mutex);
        cache.shift_scene = base;
        cache.shift_gaze = gaze;
        cache.shift_rays = job.settings.search_rays;
        cache.shift = shift;
      }
    }
    if (stale()) return nullptr;
    result->hoe_shift_mm = shift;

    TraceOptions o;
    o.rays = job.settings.rays;
    o.hoe_shift_mm = shift;
    o.keep_rays = true;
    std::shared_ptr<const std::vector<TracedRay>> diffracted;
    {
      std::lock_guard lock(cache.mutex);
      if (cache.diffraction && cache.diffraction_scene && *cache.diffraction_scene == base &&
          cache.diffraction_shift == shift && cache.diffraction_rays == o.rays)
        diffracted = cache.diffraction;
    }
    result->reused_diffraction = diffracted != nullptr;
    if (!diffracted) {
      diffracted = std::make_shared<const std::vector<TracedRay>>(diffractScene(job.scene, o));
      std::lock_guard lock(cache.mutex);
      cache.diffraction_scene = base;
      cache.diffraction_shift = shift;
      cache.diffraction_rays = o.rays;
      cache.diffraction = diffracted;
    }
    if (stale()) return nullptr;
    result->trace = evaluateGaze(job.scene, *diffracted, o);
    result->grid = projectorGrid(job.scene.projector, o.rays);
    result->cloud = gratingVectorCloud(job.scene, result->trace.ray_list, shift);
  } catch (const Superseded&) {
    return nullptr;
  } catch (const std::exception& e) {
    result->error = e.what();
  }
  result->compute_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
  return result;
}

}  // namespace fovea::widgets
