#pragma once
// Live tracing for the studio: every scene edit, drag or gaze change asks for a new trace;
// the trace runs on a worker thread, never on the GUI thread.
//  - Requests are coalesced: any number of request() calls in one event-loop turn (or while
//    a trace runs) become one job with the latest scene.
//  - Stale results are dropped: a job whose request was superseded stops at its next
//    checkpoint (between trace stages and between the x_p search's evaluations) and its
//    result is never delivered; only the newest request's result reaches resultReady().
//  - The gaze-independent half (diffractScene) is cached: a gaze change without "HOE follows
//    gaze" only re-evaluates the pupil (evaluateGaze, ~1 ms).
//  - "HOE follows gaze": the lateral HOE shift x_p(alpha) at the gaze from the one x_p
//    source (model/analysis/hoe_travel.h hoeTravel with the scene's view.xp_rule: yaw -> HOE
//    local x, pitch -> local y, each searched at the other component zero; what `fovea-cli
//    sweep` reports) is found first, then applied to the trace.
//  - The FOV shown (LiveTraceResult::fov) is the exact one (model/analysis/trace_fov.h), the
//    number `fovea-cli trace` prints as fov_deg for the same scene, gaze and shift.
//  - Coarse while the hand moves (request(..., TraceDetail::Coarse), during a slider or
//    handle drag): few rays (coarse_rays) and x_p interpolated in the gaze study's table
//    (devices/bench/follow_gaze_table.h, computed in the background for the scene once it
//    follows the gaze; until it exists the last applied x_p), no grating-vector cloud. A
//    coarse trace is cheap (< 1 ms: a gaze move re-evaluates the pupil, a handle move traces
//    coarse_rays; benchmarks/bench_live_trace.cpp), so it runs at once on the calling (GUI)
//    thread and resultReady() is emitted before request() returns: the view draws each move's
//    rays in the same frame as the moved element, with no worker round trip through a busy
//    event loop. A refined job still running is superseded. When no coarse request came for
//    kRefineIdle_ms the newest scene is traced refined (on the worker: all rays, x_p
//    searched), replacing the coarse view.

#include <QObject>
#include <QThreadPool>

#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "devices/bench/follow_gaze_table.h"
#include "model/physics/grating_cloud.h"
#include "model/physics/trace.h"
#include "model/scene/scene.h"

class QTimer;

namespace fovea::widgets {

enum class TraceDetail { Refined, Coarse };

struct LiveTraceSettings {
  int rays = 4000;           // rays per wavelength of the displayed trace
  int search_rays = 1000;    // unused: x_p comes from hoe_travel.h (exact FOV, ray count irrelevant)
  int coarse_rays = 500;     // rays per wavelength of a coarse (dragging) trace
  bool follow_gaze = false;  // apply x_p(alpha)
  bool operator==(const LiveTraceSettings&) const = default;
};

struct LiveTraceResult {
  quint64 generation = 0;
  Scene scene;  // the scene that was traced (its gaze included)
  LiveTraceSettings settings;
  std::array<double, 2> hoe_shift_mm{0, 0};  // x_p applied (zero unless follow_gaze)
  std::array<int, 2> grid{0, 0};             // projector ray grid (columns, rows) per wavelength
  TraceResult trace;                         // ray_list filled, wavelength blocks of grid[0]*grid[1]
  FovDeg fov;                                // the exact FOV (trace_fov.h), what the docks show
  FovDeg fov_dense;                          // the dense continuous FOV of `trace`'s rays (comparison)
  std::vector<GratingVectorSample> cloud;
  double compute_ms = 0;
  bool reused_diffraction = false;  // only the gaze stage ran
  TraceDetail detail = TraceDetail::Refined;
  std::string shift_source;  // where x_p came from: "search", "gaze-study table", "last applied"
  std::string error;         // non-empty: the trace failed (message)
};

class LiveTrace : public QObject {
  Q_OBJECT
 public:
  explicit LiveTrace(QObject* parent = nullptr);
  ~LiveTrace() override;  // cancels the running job and waits for it

  // Asks for a trace of `scene`; coalesced (see header comment). A coarse request schedules
  // the refined trace kRefineIdle_ms after the last one.
  void request(const Scene& scene, const LiveTraceSettings& settings, TraceDetail detail = TraceDetail::Refined);
  static constexpr int kRefineIdle_ms = 150;
  // Whether the x_p table of the gaze study is ready for the newest scene.
  bool hasShiftTable() const { return table_.has_value(); }
  const LiveTraceSettings& settings() const { return settings_; }

  std::shared_ptr<const LiveTraceResult> latest() const { return latest_; }
  bool isBusy() const { return running_ || pending_.has_value(); }
  // Runs the event loop until the newest request's result arrived (true) or timeout.
  bool waitForIdle(int timeout_ms = 60000);

  // Counters for tests and the status line.
  quint64 requests() const { return requests_; }
  quint64 newestGeneration() const { return generation_; }
  quint64 jobsStarted() const { return started_; }
  quint64 resultsDelivered() const { return delivered_; }
  quint64 resultsDropped() const { return dropped_; }

 signals:
  void resultReady(std::shared_ptr<const fovea::widgets::LiveTraceResult> result);
  void busyChanged(bool busy);

 private:
  struct Job {
    quint64 generation = 0;
    Scene scene;
    LiveTraceSettings settings;
    TraceDetail detail = TraceDetail::Refined;
    std::optional<devices::FollowGazeTable> table;  // coarse x_p
    std::array<double, 2> last_shift{0, 0};         // coarse x_p without a table
  };
  struct Cache;
  void startPending();
  void traceCoarseNow(const Scene& scene, const LiveTraceSettings& settings);
  void adoptShiftTable();  // the gaze study's x_p table, once its background task finished
  void jobFinished(std::shared_ptr<LiveTraceResult> result);
  static std::shared_ptr<LiveTraceResult> run(const Job& job, Cache& cache, const std::atomic<quint64>& newest);

  QThreadPool pool_;
  std::shared_ptr<Cache> cache_;
  std::shared_ptr<std::atomic<quint64>> newest_;
  std::optional<Job> pending_;
  LiveTraceSettings settings_;
  bool running_ = false;
  bool startQueued_ = false;
  quint64 generation_ = 0;
  void updateShiftTable(const Scene& scene);
  std::shared_ptr<const LiveTraceResult> latest_;
  quint64 deliveredGeneration_ = 0;
  QTimer* refineTimer_ = nullptr;
  std::optional<Job> refineNext_;  // the scene and settings the idle refine traces
  std::unique_ptr<devices::FollowGazeTableTask> tableTask_;
  std::optional<Scene> tableScene_;  // the scene (gaze zeroed) the table task computes for
  std::optional<devices::FollowGazeTable> table_;
  quint64 requests_ = 0, started_ = 0, delivered_ = 0, dropped_ = 0;
};

}  // namespace fovea::widgets

Q_DECLARE_METATYPE(std::shared_ptr<const fovea::widgets::LiveTraceResult>)
