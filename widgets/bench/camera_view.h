#pragma once
// Live camera image, scaled to fit with its aspect kept, a crosshair on the optical centre
// and a caption (camera, frame number, exposure). Grey 8-bit frames.
#include <QImage>
#include <QString>
#include <QWidget>

namespace fovea::widgets {

class CameraView : public QWidget {
  Q_OBJECT
 public:
  explicit CameraView(QWidget* parent = nullptr);
  void setFrame(const QImage& image, const QString& caption);
  void setCrosshair(bool on);
  void setBanner(const QString& text);  // drawn in the top-left corner ("VIRTUAL")
  const QImage& frame() const { return image_; }
  QSize sizeHint() const override { return {400, 300}; }
  QSize minimumSizeHint() const override { return {160, 120}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  QImage image_;
  QString caption_, banner_;
  bool crosshair_ = true;
};

}  // namespace fovea::widgets
