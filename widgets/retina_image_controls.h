#pragma once
// The Retina image mode's options (Foveated preview dock, issue 29): speckle (off or N independent
// patterns per laser), its grain (a canvas pixel or the pupil's) and the lateral colour (one
// geometric calibration for all lasers, or each laser warped on its own) — the studio's side of
// `fovea-cli retina-image --speckle N --speckle-grain pixel|pupil --seed S --per-laser-calibration`. One
// compact row (the words in the tooltips), so that the retinal image keeps its place in the dock
// at 1366 x 768. Holds the choices only; the preview's
// worker turns them into model/image/retina_image.h's RetinaImageOptions.

#include <QWidget>

class QComboBox;
class QSpinBox;

namespace fovea::widgets {

struct RetinaPreviewOptions {
  int speckle_patterns = 0;  // 0: speckle off
  bool speckle_grain_pupil = false;
  bool per_laser_calibration = false;
  int speckle_seed = 1;  // the speckle patterns' seed (retina_image.h speckle_seed; fovea-cli --seed)
  bool operator==(const RetinaPreviewOptions&) const = default;
};

class RetinaImageControls : public QWidget {
  Q_OBJECT
 public:
  static constexpr int kMaxSpecklePatterns = 16;
  static constexpr int kMaxSpeckleSeed = 999;  // three digits keep the row within the dock at 1366 x 768

  explicit RetinaImageControls(QWidget* parent = nullptr);
  RetinaPreviewOptions options() const;
  void setOptions(const RetinaPreviewOptions& options);

 signals:
  void changed();

 private:
  QSpinBox* speckle_ = nullptr;
  QSpinBox* seed_ = nullptr;
  QComboBox* grain_ = nullptr;
  QComboBox* calibration_ = nullptr;
};

}  // namespace fovea::widgets
