#pragma once
// One motorised axis on its own thread: the thread owns the Stage (and so the transport and
// its handle), runs submitted commands in order and polls the state when idle, publishing
// snapshots. Other threads (the GUI) only submit, read snapshots and request an e-stop.
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "devices/stage/stage.h"
#include "model/scene/scene.h"

namespace fovea::devices {

struct AxisSnapshot {
  std::string element, axis, controller, serial, stage_model, unit;
  bool is_virtual = false;
  bool connected = false;
  bool busy = false;              // a command is running
  AxisState state;                // stage coordinates
  double element_position = 0.0;  // state.position + home_offset (valid when state.known)
  std::string last_error;
  std::string controller_setup;  // what connect read (and wrote), in words (describeSetup)
};

class AxisWorker {
 public:
  using Command = std::function<void(Stage&)>;
  // idle_poll: status poll period while idle. reconnect_interval: after a link loss, how
  // often the idle worker tries to reopen it (a replugged cube comes back by itself).
  AxisWorker(std::unique_ptr<Stage> stage, StageBinding binding, bool is_virtual,
             std::chrono::milliseconds idle_poll = std::chrono::milliseconds(200),
             std::chrono::milliseconds reconnect_interval = std::chrono::milliseconds(1000));
  ~AxisWorker();
  AxisWorker(const AxisWorker&) = delete;
  AxisWorker& operator=(const AxisWorker&) = delete;

  // Runs on the worker thread; the future carries the command's exception, if any.
  std::future<void> submit(Command command);
  // Immediate stop: queued commands are dropped, the running one is interrupted.
  void emergencyStop();
  AxisSnapshot snapshot() const;
  void setListener(std::function<void(const AxisSnapshot&)> listener);
  const StageBinding& binding() const { return binding_; }

 private:
  void run();
  void publish(Stage& s, const std::string& error);

  std::unique_ptr<Stage> stage_;
  StageBinding binding_;
  bool is_virtual_;
  std::chrono::milliseconds idle_poll_, reconnect_interval_;
  bool ever_connected_ = false;  // worker thread only
  std::chrono::steady_clock::time_point last_attempt_{};
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::pair<Command, std::promise<void>>> queue_;
  AxisSnapshot snapshot_;
  std::mutex listener_mutex_;  // guards listener_ and every call of it
  std::function<void(const AxisSnapshot&)> listener_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace fovea::devices
