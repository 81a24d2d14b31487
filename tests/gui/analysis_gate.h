#pragma once
// A gated evaluator for the analysis runner (AnalysisRunner::setEvaluator): runs the real
// analysis, but its first progress report - the first sample done - blocks the worker until
// the test calls open(). A test cancels at that known point instead of sleeping and hoping
// the study is still running. Destroying the gate opens it and restores runAnalysis().
#include <condition_variable>
#include <memory>
#include <mutex>

#include "widgets/analyses/analysis_runner.h"

namespace fovea::testing {

class AnalysisGate {
 public:
  explicit AnalysisGate(widgets::AnalysisRunner* runner) : runner_(runner), state_(std::make_shared<State>()) {
    runner_->setEvaluator([state = state_](const QString& id, const Scene& scene, const widgets::AnalysisParams& params,
                                           const StudyControl& control) {
      StudyControl held = control;
      held.on_progress = [state, &control](double f) {
        {
          std::unique_lock lock(state->m);
          ++state->reports;
          state->last_fraction = f;
          state->reached = true;
          state->cv.wait(lock, [&] { return state->open; });
        }
        if (control.on_progress) control.on_progress(f);
      };
      return widgets::runAnalysis(id, scene, params, held);
    });
  }
  ~AnalysisGate() {
    open();
    if (runner_) runner_->setEvaluator(nullptr);
  }
  AnalysisGate(const AnalysisGate&) = delete;
  AnalysisGate& operator=(const AnalysisGate&) = delete;

  // True once a run has reported its first progress and is held there.
  bool reached() const {
    std::lock_guard lock(state_->m);
    return state_->reached;
  }
  void open() {
    std::lock_guard lock(state_->m);
    state_->open = true;
    state_->cv.notify_all();
  }
  // Progress reports seen (held or passed) and the last fraction reported.
  int reports() const {
    std::lock_guard lock(state_->m);
    return state_->reports;
  }
  double lastFraction() const {
    std::lock_guard lock(state_->m);
    return state_->last_fraction;
  }

 private:
  struct State {
    std::mutex m;
    std::condition_variable cv;
    bool reached = false, open = false;
    int reports = 0;
    double last_fraction = 0;
  };
  QPointer<widgets::AnalysisRunner> runner_;
  std::shared_ptr<State> state_;
};

}  // namespace fovea::testing
