#pragma once
// Time for the virtual bench: a simulated clock that jumps (tests: instant, deterministic)
// or the steady wall clock (the studio: moves take their real time).
#include <atomic>
#include <chrono>
#include <thread>

namespace fovea::devices {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual double now() const = 0;          // seconds
  virtual void waitUntil(double t_s) = 0;  // simulated: jump; steady: sleep
};

// Thread-safe: several axis threads of one virtual bench may share it (time only moves on).
class SimulatedClock : public Clock {
 public:
  double now() const override { return t_.load(); }
  void waitUntil(double t_s) override {
    double cur = t_.load();
    while (t_s > cur && !t_.compare_exchange_weak(cur, t_s)) {
    }
  }
  void advance(double dt_s) { waitUntil(t_.load() + dt_s); }

 private:
  std::atomic<double> t_{0.0};
};

class SteadyClock : public Clock {
 public:
  double now() const override {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void waitUntil(double t_s) override {
    const double dt = t_s - now();
    if (dt > 0) std::this_thread::sleep_for(std::chrono::duration<double>(dt));
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace fovea::devices
