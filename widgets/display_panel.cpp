#include "widgets/display_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

#include "model/color/srgb.h"
#include "viz/scene_actors.h"

namespace fovea::widgets {

DisplayPanel::DisplayPanel(QWidget* parent) : QWidget(parent) {
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(6, 6, 6, 6);
  auto* form = new QFormLayout;
  rays_ = new QCheckBox(tr("Ray fans projector → HOE → eye"), this);
  rays_->setObjectName("showRays");
  rays_->setChecked(true);
  rays_->setToolTip(
      tr("Draw the traced rays from the projector through the HOE into the eye, coloured by "
         "diffraction efficiency (dashed after the HOE when a ray misses the pupil)"));
  effmap_ = new QCheckBox(tr("Efficiency map on the HOE"), this);
  effmap_->setObjectName("showEffmap");
  effmap_->setToolTip(
      tr("Colour the HOE by the efficiency with which it sends the projector's light into the "
         "pupil"));
  fan_ = new QComboBox(this);
  fan_->setObjectName("fanPattern");
  fan_->addItems({tr("Horizontal fan"), tr("Vertical fan"), tr("Grid")});
  fan_->setToolTip(
      tr("Which projector rays the 3-D view draws: a horizontal or a vertical fan through the "
         "field's centre, or a grid over the whole field"));
  fanRays_ = new QSpinBox(this);
  fanRays_->setObjectName("fanRays");
  fanRays_->setRange(3, 200);
  fanRays_->setValue(25);
  fanRays_->setToolTip(
      tr("Rays drawn per fan (per grid row for the grid), per wavelength: drawing only, the FOV "
         "numbers come from the traced rays"));
  traceRays_ = new QSpinBox(this);
  traceRays_->setObjectName("traceRays");
  traceRays_->setRange(200, 40000);
  traceRays_->setSingleStep(500);
  traceRays_->setValue(4000);
  traceRays_->setKeyboardTracking(false);
  traceRays_->setToolTip(tr("Rays per wavelength over the projector field (FOV numbers, retina view, map)"));
  outer->addWidget(rays_);
  outer->addWidget(effmap_);
  form->addRow(tr("Fan"), fan_);
  form->addRow(tr("Rays per fan"), fanRays_);
  form->addRow(tr("Traced rays / λ"), traceRays_);
  outer->addLayout(form);
  auto* group = new QGroupBox(tr("Wavelengths"), this);
  wavelengthBox_ = new QVBoxLayout(group);
  outer->addWidget(group);
  outer->addStretch(1);

  for (QCheckBox* c : {rays_, effmap_}) connect(c, &QCheckBox::toggled, this, &DisplayPanel::overlayOptionsChanged);
  connect(fan_, &QComboBox::currentIndexChanged, this, &DisplayPanel::overlayOptionsChanged);
  connect(fanRays_, &QSpinBox::valueChanged, this, &DisplayPanel::overlayOptionsChanged);
  connect(traceRays_, &QSpinBox::valueChanged, this, &DisplayPanel::traceRaysChanged);
}

viz::TraceOverlayOptions DisplayPanel::overlayOptions() const {
  viz::TraceOverlayOptions o;
  o.rays = rays_->isChecked();
  o.efficiency_map = effmap_->isChecked();
  o.fan = static_cast<viz::FanPattern>(fan_->currentIndex());
  o.fan_rays = fanRays_->value();
  o.hidden_wavelengths_nm = hidden_;
  return o;
}

int DisplayPanel::traceRays() const {
  return traceRays_->value();
}
void DisplayPanel::setTraceRays(int rays) {
  traceRays_->setValue(rays);
}
void DisplayPanel::setShowRays(bool on) {
  rays_->setChecked(on);
}
void DisplayPanel::setShowEfficiencyMap(bool on) {
  effmap_->setChecked(on);
}
void DisplayPanel::setFanPattern(viz::FanPattern fan) {
  fan_->setCurrentIndex(static_cast<int>(fan));
}

void DisplayPanel::setWavelengths(const std::vector<double>& wavelengths) {
  bool same = wavelengths.size() == toggles_.size();
  for (std::size_t i = 0; same && i < wavelengths.size(); ++i) same = toggles_[i].first == wavelengths[i];
  if (same) return;
  for (auto& [nm, box] : toggles_) delete box;
  toggles_.clear();
  for (double nm : wavelengths) {
    auto* box = new QCheckBox(QStringLiteral("%1 nm").arg(nm), this);
    box->setObjectName(QStringLiteral("wavelength%1").arg(std::lround(nm)));
    box->setToolTip(tr("Show the %1 nm rays (and their layer's efficiency map); hidden ones are still traced").arg(nm));
    const auto c = color::wavelengthColor(nm);
    box->setStyleSheet(QStringLiteral("QCheckBox { color: rgb(%1,%2,%3); font-weight: bold; }")
                           .arg(std::lround(c[0] * 200 + 30))
                           .arg(std::lround(c[1] * 200 + 30))
                           .arg(std::lround(c[2] * 200 + 30)));
    box->setChecked(std::none_of(hidden_.begin(), hidden_.end(), [nm](double h) { return std::abs(h - nm) < 1e-6; }));
    connect(box, &QCheckBox::toggled, this, [this, nm](bool on) { setWavelengthShown(nm, on); });
    wavelengthBox_->addWidget(box);
    toggles_.emplace_back(nm, box);
  }
}

void DisplayPanel::setWavelengthShown(double nm, bool shown) {
  const auto it = std::find_if(hidden_.begin(), hidden_.end(), [nm](double h) { return std::abs(h - nm) < 1e-6; });
  const bool wasShown = it == hidden_.end();
  if (wasShown == shown) return;
  if (shown)
    hidden_.erase(it);
  else
    hidden_.push_back(nm);
  if (QCheckBox* box = wavelengthToggle(nm)) {
    QSignalBlocker block(box);
    box->setChecked(shown);
  }
  emit overlayOptionsChanged();
}

QCheckBox* DisplayPanel::wavelengthToggle(double nm) const {
  for (const auto& [w, box] : toggles_)
    if (std::abs(w - nm) < 1e-6) return box;
  return nullptr;
}

}  // namespace fovea::widgets
