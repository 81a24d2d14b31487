#include "widgets/live_trace.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QTimer>

#include <mutex>
#include <stdexcept>

#include "model/analysis/hoe_travel.h"
#include "model/analysis/trace_fov.h"
#include "model/physics/projector_rays.h"
#include "model/vector_state.h"

namespace fovea::widgets {

namespace {
struct Superseded {};
}  // namespace

// Results of the expensive stages of the last jobs, reused by the next ones (one diffraction
// slot per detail, so a drag's coarse traces keep the refined one). A coarse trace on the GUI
// thread may run while a refined job finishes on the worker: every access holds the mutex
// (briefly: the slots hold shared pointers).
struct LiveTrace::Cache {
  std::mutex mutex;
  // diffractScene() depends on everything but the gaze.
  struct Diffraction {
    std::optional<Scene> scene;
    std::array<double, 2> shift{0, 0};
    int rays = 0;
    std::shared_ptr<const std::vector<TracedRay>> rays_out;
  } diffraction[2];
  // x_p for one (scene without gaze, gaze).
  std::optional<Scene> shift_scene;
  std::array<double, 2> shift_gaze{0, 0};
  std::array<double, 2> shift{0, 0};
};

LiveTrace::LiveTrace(QObject* parent)
    : QObject(parent), cache_(std::make_shared<Cache>()), newest_(std::make_shared<std::atomic<quint64>>(0)) {
  qRegisterMetaType<std::shared_ptr<const LiveTraceResult>>();
  pool_.setMaxThreadCount(1);  // the trace itself is parallel (TBB)
  refineTimer_ = new QTimer(this);
  refineTimer_->setSingleShot(true);
  refineTimer_->setInterval(kRefineIdle_ms);
  connect(refineTimer_, &QTimer::timeout, this, [this] {
    if (!refineNext_) return;
    Job next = std::move(*refineNext_);
    refineNext_.reset();
    request(next.scene, next.settings, TraceDetail::Refined);
  });
}

LiveTrace::~LiveTrace() {
  newest_->store(~quint64{0});  // every running job is stale now
  pool_.waitForDone();
}

void LiveTrace::request(const Scene& scene, const LiveTraceSettings& settings, TraceDetail detail) {
  ++requests_;
  settings_ = settings;
  if (detail == TraceDetail::Coarse) {
    traceCoarseNow(scene, settings);
    return;
  }
  const bool wasBusy = isBusy();
  pending_ = Job{++generation_, scene, settings, detail, {}, {0, 0}};
  newest_->store(generation_);
  refineTimer_->stop();
  refineNext_.reset();
  if (settings.follow_gaze) updateShiftTable(scene);
  if (!wasBusy) emit busyChanged(true);
  if (!running_ && !startQueued_) {
    startQueued_ = true;
    QTimer::singleShot(0, this, [this] {
      startQueued_ = false;
      startPending();
    });
  }
}

void LiveTrace::traceCoarseNow(const Scene& scene, const LiveTraceSettings& settings) {
  const bool wasBusy = isBusy();
  pending_.reset();  // a queued job is superseded; a running refined one stops at its next checkpoint
  newest_->store(++generation_);
  refineNext_ = Job{0, scene, settings, TraceDetail::Refined, {}, {0, 0}};
  refineTimer_->start();  // restarted by every move: fires when the hand rests
  adoptShiftTable();
  Job job{generation_, scene, settings, TraceDetail::Coarse, table_, {0, 0}};
  if (latest_) job.last_shift = latest_->hoe_shift_mm;
  ++started_;
  std::shared_ptr<LiveTraceResult> result = run(job, *cache_, *newest_);
  latest_ = result;
  deliveredGeneration_ = result->generation;
  ++delivered_;
  emit resultReady(latest_);
  if (wasBusy && !isBusy()) emit busyChanged(false);
}

void LiveTrace::adoptShiftTable() {
  if (!tableTask_) return;
  if (auto t = tableTask_->table()) {
    table_ = std::move(t);
    tableTask_.reset();
  }
}

void LiveTrace::updateShiftTable(const Scene& scene) {
  Scene base = scene;
  base.eye.gaze_deg = {0.0, 0.0};
  if (tableScene_ && *tableScene_ == base) return;
  // A new design: its gaze study in the background; the old table serves coarse traces
  // until the new one is ready (a drag moves the design little).
  tableScene_ = base;
  tableTask_ = std::make_unique<devices::FollowGazeTableTask>(base);
}

void LiveTrace::startPending() {
  if (running_ || !pending_) return;
  Job job = std::move(*pending_);
  pending_.reset();
  adoptShiftTable();
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
  // Only the newest request's result (a coarse one was delivered when it was asked for).
  const bool deliver = result && result->generation == generation_;
  if (deliver) {
    latest_ = result;
    deliveredGeneration_ = result->generation;
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
  while (isBusy() || startQueued_ || refineTimer_->isActive()) {
    if (t.elapsed() > timeout_ms) return false;
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  }
  return latest_ && latest_->generation == generation_;
}

std::shared_ptr<LiveTraceResult> LiveTrace::run(const Job& job, Cache& cache, const std::atomic<quint64>& newest) {
  clearUpperVectorState();  // a pool thread that ran Qt code (model/vector_state.h)
  QElapsedTimer timer;
  timer.start();
  const bool coarse = job.detail == TraceDetail::Coarse;
  // A coarse job runs to its end (it is short and its result is shown); a refined one stops
  // at its next checkpoint once superseded.
  auto stale = [&] { return !coarse && newest.load() != job.generation; };
  auto result = std::make_shared<LiveTraceResult>();
  result->generation = job.generation;
  result->scene = job.scene;
  result->settings = job.settings;
  result->detail = job.detail;
  try {
    Scene base = job.scene;  // everything the diffraction depends on
    base.eye.gaze_deg = {0.0, 0.0};
    const auto gaze = job.scene.eye.gaze_deg;
    std::array<double, 2> shift{0.0, 0.0};
    if (coarse && job.settings.follow_gaze && (gaze[0] != 0.0 || gaze[1] != 0.0)) {
      // x_p interpolated in the gaze study's table (absolute, as the search's; zero gaze
      // components keep 0 as the refined trace does), else the last applied one.
      if (job.table) {
        const auto& t = *job.table;
        shift = {gaze[0] != 0.0 ? devices::interpolateClamped(t.gazes_deg, t.shift_x_mm, gaze[0]) : 0.0,
                 gaze[1] != 0.0 ? devices::interpolateClamped(t.gazes_deg, t.shift_y_mm, gaze[1]) : 0.0};
        result->shift_source = "gaze-study table";
      } else {
        shift = job.last_shift;
        result->shift_source = "last applied";
      }
    } else if (job.settings.follow_gaze && (gaze[0] != 0.0 || gaze[1] != 0.0)) {
      result->shift_source = "search";
      bool cached = false;
      {
        std::lock_guard lock(cache.mutex);
        if (cache.shift_scene && *cache.shift_scene == base && cache.shift_gaze == gaze) {
          shift = cache.shift;
          cached = true;
        }
      }
      if (!cached) {
        // The one x_p source (model/analysis/hoe_travel.h: sweep's x_p, the scene's rule),
        // its evaluator wrapped only to stop a superseded job between evaluations.
        const FovEvaluator inner = hoeTravelEvaluator();
        const FovEvaluator eval = [&](const Scene& s, const FovQuery& q) {
          if (stale()) throw Superseded{};
          return inner(s, q);
        };
        shift = hoeTravel(job.scene, gaze, sceneXpRule(job.scene), eval).shift_mm;
        std::lock_guard lock(cache.mutex);
        cache.shift_scene = base;
        cache.shift_gaze = gaze;
        cache.shift = shift;
      }
    }
    if (stale()) return nullptr;
    result->hoe_shift_mm = shift;

    TraceOptions o;
    o.rays = coarse ? job.settings.coarse_rays : job.settings.rays;
    o.hoe_shift_mm = shift;
    o.keep_rays = true;
    Cache::Diffraction& slot = cache.diffraction[coarse ? 1 : 0];
    std::shared_ptr<const std::vector<TracedRay>> diffracted;
    {
      std::lock_guard lock(cache.mutex);
      if (slot.rays_out && slot.scene && *slot.scene == base && slot.shift == shift && slot.rays == o.rays)
        diffracted = slot.rays_out;
    }
    result->reused_diffraction = diffracted != nullptr;
    if (!diffracted) {
      diffracted = std::make_shared<const std::vector<TracedRay>>(diffractScene(job.scene, o));
      std::lock_guard lock(cache.mutex);
      slot.scene = base;
      slot.shift = shift;
      slot.rays = o.rays;
      slot.rays_out = diffracted;
    }
    if (stale()) return nullptr;
    result->trace = evaluateGaze(job.scene, *diffracted, o);
    result->grid = projectorGrid(job.scene.projector, o.rays);
    // The FOV the docks show: the exact one, as `fovea-cli trace` and `sweep` (trace_fov.h).
    TraceOptions fo = o;
    fo.gaze_deg = gaze;
    result->fov = exactTraceFov(job.scene, fo);
    result->fov_dense = denseTraceFov(result->trace, o.efficiency_threshold);
    if (!coarse) result->cloud = gratingVectorCloud(job.scene, result->trace.ray_list, shift);
  } catch (const Superseded&) {
    return nullptr;
  } catch (const std::exception& e) {
    result->error = e.what();
  }
  result->compute_ms = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
  return result;
}

}  // namespace fovea::widgets
