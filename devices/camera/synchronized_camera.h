#pragma once
// A camera shared by several threads (the studio's live view and a calibration capture):
// every call goes to the wrapped camera under one mutex, so frames are taken one at a time.
#include <memory>
#include <mutex>

#include "devices/camera/camera.h"

namespace fovea::devices {

class SynchronizedCamera : public Camera {
 public:
  explicit SynchronizedCamera(std::shared_ptr<Camera> inner) : inner_(std::move(inner)) {}
  void open() override {
    std::lock_guard l(m_);
    inner_->open();
  }
  void close() override {
    std::lock_guard l(m_);
    inner_->close();
  }
  bool isOpen() const override {
    std::lock_guard l(m_);
    return inner_->isOpen();
  }
  Frame grab() override {
    std::lock_guard l(m_);
    return inner_->grab();
  }
  DeviceInfo info() const override {
    std::lock_guard l(m_);
    return inner_->info();
  }
  double now() const override { return inner_->now(); }
  bool hasExposure() const override { return inner_->hasExposure(); }
  std::optional<double> exposure() const override {
    std::lock_guard l(m_);
    return inner_->exposure();
  }
  void setExposure(double s) override {
    std::lock_guard l(m_);
    inner_->setExposure(s);
  }
  bool hasGain() const override { return inner_->hasGain(); }
  std::optional<double> gain() const override {
    std::lock_guard l(m_);
    return inner_->gain();
  }
  void setGain(double g) override {
    std::lock_guard l(m_);
    inner_->setGain(g);
  }
  Camera& inner() { return *inner_; }

 private:
  std::shared_ptr<Camera> inner_;
  mutable std::mutex m_;
};

}  // namespace fovea::devices
