#include "widgets/analyses/analysis_runner.h"

#include <QCoreApplication>

#include <exception>

#include "model/scene/scene_io.h"
#include "model/vector_state.h"

namespace fovea::widgets {

AnalysisRunner::AnalysisRunner(QObject* parent) : QObject(parent) {
  qRegisterMetaType<fovea::widgets::AnalysisResult>();
}

AnalysisRunner::~AnalysisRunner() {
  if (cancel_) cancel_->store(true);
  if (worker_) worker_->wait();
}

bool AnalysisRunner::start(const QString& id, const Scene& scene, const AnalysisParams& params) {
  if (running_) return false;
  running_ = true;
  current_ = id;
  const int generation = ++generation_;
  cancel_ = std::make_shared<std::atomic<bool>>(false);
  auto cancelFlag = cancel_;
  auto lastPermille = std::make_shared<std::atomic<int>>(-1000);

  AnalysisResult base;
  base.id = id;
  base.params = params;
  base.sceneName = QString::fromStdString(scene.name);
  base.sceneText = serializeScene(scene);
  const Scene snapshot = scene;
  Evaluator evaluate = evaluator_ ? evaluator_
                                  : Evaluator([](const QString& a, const Scene& s, const AnalysisParams& p,
                                                 const StudyControl& c) { return runAnalysis(a, s, p, c); });

  worker_ = QThread::create([this, generation, cancelFlag, lastPermille, base, snapshot, evaluate]() mutable {
    clearUpperVectorState();  // inherited from the GUI thread (model/vector_state.h)
    QElapsedTimer clock;
    clock.start();
    StudyControl control;
    control.cancel = cancelFlag.get();
    control.on_progress = [this, generation, lastPermille, id = base.id](double f) {
      const int pm = static_cast<int>(f * 1000.0);
      if (pm < 1000 && pm - lastPermille->load() < 5) return;  // at most 200 steps
      lastPermille->store(pm);
      QMetaObject::invokeMethod(
          this,
          [this, generation, id, f] {
            if (generation == generation_ && running_) emit progress(id, f);
          },
          Qt::QueuedConnection);
    };
    QString kind = "finished", message;
    try {
      std::optional<nlohmann::json> out = evaluate(base.id, snapshot, base.params, control);
      if (out)
        base.json = std::make_shared<const nlohmann::json>(std::move(*out));
      else
        kind = "cancelled";
    } catch (const std::exception& e) {
      kind = "failed";
      message = QString::fromUtf8(e.what());
    }
    base.seconds = clock.elapsed() / 1000.0;
    QMetaObject::invokeMethod(
        this, [this, generation, kind, base, message] { deliver(generation, kind, base, message); },
        Qt::QueuedConnection);
  });
  connect(worker_, &QThread::finished, worker_, &QObject::deleteLater);
  emit started(id);
  worker_->start();
  return true;
}

void AnalysisRunner::cancel() {
  if (running_ && cancel_) cancel_->store(true);
}

void AnalysisRunner::deliver(int generation, const QString& kind, const AnalysisResult& result,
                             const QString& message) {
  if (generation != generation_ || !running_) return;
  const bool wasCancelled = cancel_ && cancel_->load();
  running_ = false;
  current_.clear();
  if (kind == "failed")
    emit failed(result.id, message);
  else if (kind == "cancelled" || wasCancelled)  // a result that arrives after Cancel is dropped
    emit cancelled(result.id);
  else
    emit finished(result);
  emit idle();
}

bool AnalysisRunner::waitForIdle(int timeoutMs) {
  QElapsedTimer t;
  t.start();
  while (running_ && t.elapsed() < timeoutMs) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    if (running_) QThread::msleep(2);
  }
  return !running_;
}

}  // namespace fovea::widgets
