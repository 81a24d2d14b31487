#pragma once
// Time for the virtual bench: a simulated clock that jumps (tests: instant, deterministic)
// or the steady wall clock (the studio: moves take their real time).
#include <chrono>
#include <thread>

namespace fovea::devices {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual double now() const = 0;          // seconds
  virtual void waitUntil(double t_s) = 0;  // simulated: jump; steady: sleep
};

class SimulatedClock : public Clock {
 public:
  double now() const override { return t_; }
  void waitUntil(double t_s) override {
    if (t_s > t_) t_ = t_s;
  }
  void advance(double dt_s) { waitUntil(t_ + dt_s); }

 private:
  double t_ = 0.0;
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
