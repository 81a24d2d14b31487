#pragma once
// Runs one analysis at a time off the GUI thread. start() snapshots the scene and the
// parameters and runs runAnalysis() on a worker QThread; progress arrives on the GUI thread
// (throttled to at most ~50 updates per second); cancel() sets the study's cancel flag, so
// the study stops before its next sample (running samples finish, never a partial result),
// and the run ends with cancelled(). Exactly one of finished(), failed() or cancelled() ends
// every started run, always on the GUI thread, followed by idle().

#include <QElapsedTimer>
#include <QObject>
#include <QPointer>
#include <QThread>

#include <atomic>
#include <functional>
#include <memory>

#include "widgets/analyses/analysis_catalog.h"

namespace fovea::widgets {

struct AnalysisResult {
  QString id;
  AnalysisParams params;
  std::shared_ptr<const nlohmann::json> json;  // the CLI-shaped result
  QString sceneName;
  std::string sceneText;  // serialized scene the result belongs to
  double seconds = 0;
};

class AnalysisRunner : public QObject {
  Q_OBJECT
 public:
  explicit AnalysisRunner(QObject* parent = nullptr);
  ~AnalysisRunner() override;  // cancels and waits for a running worker

  // False (and nothing happens) while a run is in progress.
  bool start(const QString& id, const Scene& scene, const AnalysisParams& params);
  void cancel();
  bool isRunning() const { return running_; }
  QString currentAnalysis() const { return current_; }
  // Blocks (processing events) until idle or `timeoutMs`; true when idle.
  bool waitForIdle(int timeoutMs);

  // What a run calls on its worker thread: runAnalysis() unless replaced. A test hook: a test
  // wraps runAnalysis() in a gate (it blocks until the test releases it) to cancel a run at a
  // known point without sleeping. Takes effect from the next start(); nullptr restores it.
  using Evaluator = std::function<std::optional<nlohmann::json>(
      const QString& id, const Scene& scene, const AnalysisParams& params, const StudyControl& control)>;
  void setEvaluator(Evaluator evaluator) { evaluator_ = std::move(evaluator); }

 signals:
  void started(const QString& id);
  void progress(const QString& id, double fraction);
  void finished(const fovea::widgets::AnalysisResult& result);
  void failed(const QString& id, const QString& message);
  void cancelled(const QString& id);
  void idle();

 private:
  void deliver(int generation, const QString& kind, const AnalysisResult& result, const QString& message);

  Evaluator evaluator_;
  QPointer<QThread> worker_;
  std::shared_ptr<std::atomic<bool>> cancel_;
  std::shared_ptr<std::atomic<int>> lastProgressPermille_;
  QString current_;
  bool running_ = false;
  int generation_ = 0;
};

}  // namespace fovea::widgets

Q_DECLARE_METATYPE(fovea::widgets::AnalysisResult)
