#pragma once
// Foveated preview (seed B.2.3): the target, the foveal image (micro-OLED), the peripheral
// image (projector) and the perceived composite, updating live as the gaze sliders move.
// The compositing runs on a worker thread (model FoveatedCompositor, which recomputes only
// what a gaze change touches); the GUI thread only shows finished frames. Requests made
// while the worker is busy are coalesced to the newest gaze. The FLIP seam figure is
// computed once the gaze has rested for a moment.
// Retina image mode (issue 29): the same target and gaze through both displays and the
// accommodating eye, as the retina receives it (model/image/retina_image.h), with an
// accommodation slider and the speckle / lateral-colour options (widgets/retina_image_controls.h);
// rendered on the same worker at kRetinaWidthPx (a target of that width as it is), coalesced the
// same way. When the scene's HOE follows the gaze (view.hoe_follows_gaze, the Gaze dock's toggle)
// the HOE is shifted by the studio's one x_p (model/analysis/hoe_travel.h, hoeTravel with the
// scene's x_p rule) at the preview's gaze, as the live trace applies it at the eye's; otherwise
// it is not shifted.

#include <QImage>
#include <QPointer>
#include <QThread>
#include <QWidget>

#include <array>
#include <optional>

#include "model/scene/scene.h"
#include "widgets/retina_image_controls.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QSlider;
class QTimer;

namespace fovea::widgets {

class SceneDocument;
class PreviewWorker;

// A titled image that keeps its aspect ratio, with optional gaze rings (degrees) drawn
// on an image spanning `fov_deg`.
class PreviewImageView : public QWidget {
  Q_OBJECT
 public:
  PreviewImageView(const QString& title, QWidget* parent = nullptr);
  void setImage(const QImage& image);
  void setRings(std::array<double, 2> fov_deg, std::array<double, 2> centre_deg, std::vector<double> radii_deg);
  const QImage& image() const { return image_; }
  QSize sizeHint() const override { return {320, heightForWidth(320)}; }
  // Title line plus the image's height at this width (16:9 until an image arrives).
  bool hasHeightForWidth() const override { return true; }
  int heightForWidth(int width) const override;

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  QString title_;
  QImage image_, scaled_;
  std::array<double, 2> fov_{0, 0}, centre_{0, 0};
  std::vector<double> radii_;
};

struct PreviewFrame {
  QImage target, foveal, peripheral, perceived;
  QImage retina;                          // Retina image mode: the retinal image (sRGB for display)
  QString retinaInfo;                     // its line-of-sight spots and powers, one line
  std::optional<double> accommodation_d;  // set in Retina image mode
  // Retina image mode: the options and HOE shift it was rendered with, and its figures
  // (model/image/retina_image.h's RetinaImageResult; the lateral colour from retina_image_figures.h).
  RetinaPreviewOptions retinaOptions;
  std::array<double, 2> hoe_shift_mm{0, 0};
  std::optional<double> speckle_contrast, speckle_expected;  // speckle on
  std::optional<double> lateral_colour_arcmin;               // at the line of sight, the largest laser's
  std::array<double, 2> gaze_deg{0, 0};
  std::array<double, 2> target_fov_deg{0, 0}, foveal_fov_deg{0, 0};
  std::array<double, 3> ring_deg{0, 0, 0};
  double update_ms = 0;
  std::optional<double> seam_flip;
  QString error;
  int generation = 0;
};

class PreviewPanel : public QWidget {
  Q_OBJECT
 public:
  explicit PreviewPanel(SceneDocument* document, QWidget* parent = nullptr);
  ~PreviewPanel() override;

  // Loads a target image (any format OpenImageIO reads) on the worker; errors show in
  // the panel's status line and leave the current target.
  void loadTarget(const QString& path);
  void setGaze(double yaw_deg, double pitch_deg);
  std::array<double, 2> gaze() const;
  enum class Mode { Displays, RetinaImage };
  void setMode(Mode mode);
  Mode mode() const;
  // Retina image mode's accommodation (diopters, 0..4 in 0.05 D steps).
  void setAccommodation(double diopters);
  double accommodation() const;
  // Retina image mode's speckle and lateral-colour options (kept for the session).
  void setRetinaOptions(const RetinaPreviewOptions& options);
  RetinaPreviewOptions retinaOptions() const;
  // Number of frames shown so far and the newest one (for tests).
  int framesShown() const { return framesShown_; }
  const PreviewFrame& lastFrame() const { return last_; }

 signals:
  void frameShown();

 private:
  friend class PreviewWorker;
  void rebuild();                 // scene or blending changed: new compositor (keeps the target)
  void requestRender(bool seam);  // coalesced
  void showFrame(const PreviewFrame& frame);
  void applyMode();  // shows the views of the current mode

  SceneDocument* document_;
  std::optional<Scene> configured_;  // the scene the compositor was last built for
  QThread thread_;
  PreviewWorker* worker_ = nullptr;
  QSlider *yaw_ = nullptr, *pitch_ = nullptr, *accommodation_ = nullptr;
  QLabel *yawLabel_ = nullptr, *pitchLabel_ = nullptr, *accommodationLabel_ = nullptr, *status_ = nullptr,
         *retinaInfo_ = nullptr;
  QComboBox* mode_ = nullptr;
  QWidget* displaysGrid_ = nullptr;
  PreviewImageView* retinaView_ = nullptr;
  RetinaImageControls* retinaControls_ = nullptr;
  QCheckBox* blend_ = nullptr;
  PreviewImageView *targetView_ = nullptr, *fovealView_ = nullptr, *peripheralView_ = nullptr,
                   *perceivedView_ = nullptr;
  QTimer* seamTimer_ = nullptr;
  bool busy_ = false;
  std::optional<bool> pending_;  // a request waiting (with or without the seam figure)
  int framesShown_ = 0;
  PreviewFrame last_;
};

}  // namespace fovea::widgets
