#pragma once
// The Bench dock's eye camera: live view (about 10 frames per second on a thread of its own)
// with crosshair, exposure and gain, and the test pattern the virtual displays show.
#include <QGroupBox>

#include <atomic>
#include <functional>
#include <thread>

#include "devices/bench/live_bench.h"
#include "model/scene/scene.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;

namespace fovea::widgets {

class CameraView;

class EyeCameraBox : public QGroupBox {
  Q_OBJECT
 public:
  EyeCameraBox(std::function<Scene()> scene, bool live_by_default, QWidget* parent = nullptr);
  ~EyeCameraBox() override;

  void setBench(devices::LiveBench* live);  // nullptr: stops and clears the view
  void start();                             // the camera loop, when Live is checked
  void stop();
  bool liveChecked() const;
  bool hasFrame() const;
  void setTestPattern(int index);  // 0 off, 1 both checkerboards, 2 projector, 3 micro-OLED, 4 white
  int testPattern() const;
  void applyExposure();
  void setBanner(const QString& text);

 signals:
  void report(const QString& text, bool error);
  void liveToggled(bool on);

 private:
  std::function<Scene()> scene_;
  devices::LiveBench* live_ = nullptr;
  CameraView* view_ = nullptr;
  QDoubleSpinBox *exposure_ = nullptr, *gain_ = nullptr;
  QCheckBox *crosshair_ = nullptr, *live_check_ = nullptr;
  QComboBox* pattern_ = nullptr;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> frame_pending_{false};
};

}  // namespace fovea::widgets
