#pragma once
// "Rays" dock: what the live trace draws — ray fans (pattern, rays per fan), the efficiency
// map on the HOE, one toggle per projector wavelength — and how many rays are traced.

#include <QWidget>

#include <vector>

#include "viz/trace_overlay.h"

class QCheckBox;
class QComboBox;
class QSpinBox;
class QVBoxLayout;

namespace fovea::widgets {

class DisplayPanel : public QWidget {
  Q_OBJECT
 public:
  explicit DisplayPanel(QWidget* parent = nullptr);

  viz::TraceOverlayOptions overlayOptions() const;
  int traceRays() const;
  void setTraceRays(int rays);
  void setShowRays(bool on);
  void setShowEfficiencyMap(bool on);
  void setFanPattern(viz::FanPattern fan);
  // One toggle per wavelength (rebuilt when the list changes; states kept by value).
  void setWavelengths(const std::vector<double>& wavelengths_nm);
  void setWavelengthShown(double wavelength_nm, bool shown);
  QCheckBox* wavelengthToggle(double wavelength_nm) const;

 signals:
  void overlayOptionsChanged();
  void traceRaysChanged(int rays);

 private:
  QCheckBox* rays_ = nullptr;
  QCheckBox* effmap_ = nullptr;
  QComboBox* fan_ = nullptr;
  QSpinBox* fanRays_ = nullptr;
  QSpinBox* traceRays_ = nullptr;
  QVBoxLayout* wavelengthBox_ = nullptr;
  std::vector<std::pair<double, QCheckBox*>> toggles_;
  std::vector<double> hidden_;
};

}  // namespace fovea::widgets
