#pragma once
// Our Qt 6 <-> VTK bridge: a QOpenGLWidget hosting a vtkGenericOpenGLRenderWindow.
// VTK's own Qt module in Debian bookworm is built against Qt 5, so we do not use it
// (docs/platform.md, quirk 1). VTK renders into its own framebuffer with
// Qt's context current; paintGL() blits that into the widget's defaultFramebufferObject().
// Mouse, wheel and key events are forwarded to a vtkRenderWindowInteractor, and VTK's
// render requests become QWidget::update().
//
// It can draw at a reduced resolution (setRenderScale), magnified into the widget: for frames
// drawn while a hand drags, as a software renderer's cost is per pixel.
//
// Call installDefaultSurfaceFormat() before the QApplication is created.

#include <QOpenGLWidget>
#include <QSize>

#include <unordered_map>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

class vtkGenericOpenGLRenderWindow;
class vtkGenericRenderWindowInteractor;
class vtkRenderer;
class vtkInteractorStyle;
class vtkCallbackCommand;
class vtkObject;

namespace fovea::viz {

// An OpenGL 3.2 core profile with depth and stencil buffers, as VTK's OpenGL2 backend needs.
void installDefaultSurfaceFormat();

class VtkGlWidget : public QOpenGLWidget {
  Q_OBJECT
 public:
  explicit VtkGlWidget(QWidget* parent = nullptr);
  ~VtkGlWidget() override;

  vtkRenderer* renderer() const;
  vtkGenericOpenGLRenderWindow* renderWindow() const;
  vtkGenericRenderWindowInteractor* interactor() const;

  // Asks for a repaint (VTK renders inside paintGL()).
  void requestRender() { update(); }
  // Renders now (makes the context current) and returns the rendered image, the same
  // pixels the user sees. Empty when OpenGL is unavailable.
  QImage renderToImage();
  // How long the last paintGL() took (VTK's render and the blit into Qt's framebuffer), ms.
  double lastPaintMs() const { return lastPaintMs_; }
  // Draws the next frames at `scale` (clamped to 0.25 .. 1) of the widget's resolution in each
  // direction, magnified bilinearly into it (ParaView's image reduction while interacting).
  // The frame keeps its look, only softer: text shrinks with the window's DPI (72 x scale),
  // line widths with the scale (restored at 1), and overlays that place things in pixels
  // multiply their pixel sizes by pixelScale() (viz/render_scale.h). Between frames the render window has the
  // widget's full size again, so picking, event positions and world <-> display conversions
  // never see the reduced one. 1 (the default): full resolution.
  void setRenderScale(double scale);
  double renderScale() const { return renderScale_; }
  // The scale setRenderScale() uses for `scale`: clamped to 0.25 .. 1, 1 for NaN or infinity.
  static double clampRenderScale(double scale);
  // The size of the last frame VTK drew (device pixels): the widget's, times renderScale().
  QSize lastRenderSize() const { return lastRenderSize_; }

 protected:
  void initializeGL() override;
  void resizeGL(int w, int h) override;
  void paintGL() override;

  void mousePressEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void keyReleaseEvent(QKeyEvent* event) override;
  void enterEvent(QEnterEvent* event) override;
  void leaveEvent(QEvent* event) override;

 private:
  static void onVtkEvent(vtkObject* caller, unsigned long eventId, void* clientData, void* callData);
  void setEventPosition(const QPointF& pos, Qt::KeyboardModifiers mods, int repeat = 0);
  int toPixels(double logical) const;
  // Scales every actor's line width in the window's renderers by renderScale() (each width
  // once; a width the application changed since is taken as its new original), or puts the
  // originals back at full resolution.
  void scaleLineWidths();

  vtkNew<vtkGenericOpenGLRenderWindow> window_;
  vtkNew<vtkRenderer> renderer_;
  vtkNew<vtkGenericRenderWindowInteractor> interactor_;
  vtkSmartPointer<vtkInteractorStyle> style_;
  vtkNew<vtkCallbackCommand> callback_;
  bool inPaint_ = false;
  bool glReady_ = false;
  double lastPaintMs_ = 0.0;
  double renderScale_ = 1.0;
  QSize lastRenderSize_;
  struct ScaledWidth {
    vtkSmartPointer<vtkObject> property;  // kept alive so its address is not reused
    float original = 1.0f;
    float scaled = 1.0f;
  };
  std::unordered_map<vtkObject*, ScaledWidth> scaledWidths_;
};

}  // namespace fovea::viz
