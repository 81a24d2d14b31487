#include "devices/bench/axis_worker.h"

#include "devices/stage/stage_binding.h"

namespace fovea::devices {

AxisWorker::AxisWorker(std::unique_ptr<Stage> stage, StageBinding binding, bool is_virtual,
                       std::chrono::milliseconds idle_poll, std::chrono::milliseconds reconnect_interval)
    : stage_(std::move(stage)),
      binding_(std::move(binding)),
      is_virtual_(is_virtual),
      idle_poll_(idle_poll),
      reconnect_interval_(reconnect_interval) {
  snapshot_.element = binding_.element;
  snapshot_.axis = binding_.axis;
  snapshot_.controller = binding_.controller;
  snapshot_.serial = binding_.serial;
  snapshot_.stage_model = binding_.stage_model;
  snapshot_.unit = stage_->config().stage.unit();
  snapshot_.is_virtual = is_virtual_;
  thread_ = std::thread([this] { run(); });
}

AxisWorker::~AxisWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  stage_->requestEmergencyStop();  // closing the bench mid-move stops the axis rather than waiting
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::future<void> AxisWorker::submit(Command command) {
  std::promise<void> p;
  auto f = p.get_future();
  {
    std::lock_guard lock(mutex_);
    queue_.emplace_back(std::move(command), std::move(p));
  }
  cv_.notify_all();
  return f;
}

void AxisWorker::emergencyStop() {
  std::deque<std::pair<Command, std::promise<void>>> dropped;
  {
    std::lock_guard lock(mutex_);
    dropped.swap(queue_);
  }
  for (auto& [cmd, p] : dropped)
    p.set_exception(std::make_exception_ptr(DeviceError(DeviceError::Kind::Usage, "cancelled by the emergency stop")));
  stage_->requestEmergencyStop();
  // An idle worker sends the stop from its own thread right away.
  submit([](Stage& s) {
    if (s.connected()) s.stop(true);
  });
}

AxisSnapshot AxisWorker::snapshot() const {
  std::lock_guard lock(mutex_);
  return snapshot_;
}

// The listener is swapped and called under listener_mutex_, so once setListener returns
// the old listener is never called again (the caller may then destroy what it captured).
void AxisWorker::setListener(std::function<void(const AxisSnapshot&)> listener) {
  std::lock_guard lock(listener_mutex_);
  listener_ = std::move(listener);
}

void AxisWorker::publish(Stage& s, const std::string& error) {
  AxisSnapshot snap;
  {
    std::lock_guard lock(mutex_);
    snapshot_.connected = s.connected();
    snapshot_.state = s.state();
    snapshot_.element_position = stageToElement(binding_, snapshot_.state.position);
    if (!error.empty()) snapshot_.last_error = error;
    if (s.connected()) snapshot_.controller_setup = describeSetup(s.controllerParameters(), s.config().stage.unit());
    snapshot_.busy = !queue_.empty();
    snap = snapshot_;
  }
  std::lock_guard lock(listener_mutex_);
  if (listener_) listener_(snap);
}

void AxisWorker::run() {
  Stage& s = *stage_;
  for (;;) {
    std::pair<Command, std::promise<void>> job;
    bool have_job = false;
    {
      std::unique_lock lock(mutex_);
      cv_.wait_for(lock, idle_poll_, [this] { return stop_ || !queue_.empty(); });
      if (stop_) break;
      if (!queue_.empty()) {
        job = std::move(queue_.front());
        queue_.pop_front();
        have_job = true;
        snapshot_.busy = true;
      }
    }
    std::string error;
    if (have_job) {
      try {
        job.first(s);
        job.second.set_value();
      } catch (const std::exception& e) {
        error = e.what();
        job.second.set_exception(std::current_exception());
      }
    } else if (s.connected()) {
      try {
        s.poll();  // live position readout while idle
      } catch (const std::exception& e) {
        error = e.what();
      }
    } else if (ever_connected_ && std::chrono::steady_clock::now() - last_attempt_ >= reconnect_interval_) {
      // Lost link: try to get it back (polling hot-plug; a replugged cube returns here).
      last_attempt_ = std::chrono::steady_clock::now();
      try {
        s.reconnect();
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    ever_connected_ = ever_connected_ || s.connected();
    publish(s, error);
  }
  // Shutdown: fail whatever is still queued.
  std::lock_guard lock(mutex_);
  for (auto& [cmd, p] : queue_)
    p.set_exception(std::make_exception_ptr(DeviceError(DeviceError::Kind::Disconnected, "axis worker shut down")));
  queue_.clear();
}

}  // namespace fovea::devices
