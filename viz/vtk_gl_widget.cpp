#include "viz/vtk_gl_widget.h"

#include <QElapsedTimer>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QSurfaceFormat>
#include <QWheelEvent>

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkActor2DCollection.h>
#include <vtkActorCollection.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkOpenGLState.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>

#include <algorithm>
#include <cmath>

namespace fovea::viz {

void installDefaultSurfaceFormat() {
  QSurfaceFormat fmt;
  fmt.setRenderableType(QSurfaceFormat::OpenGL);
  fmt.setVersion(3, 2);
  fmt.setProfile(QSurfaceFormat::CoreProfile);
  fmt.setSwapBehavior(QSurfaceFormat::DoubleBuffer);
  fmt.setRedBufferSize(8);
  fmt.setGreenBufferSize(8);
  fmt.setBlueBufferSize(8);
  fmt.setDepthBufferSize(24);
  fmt.setStencilBufferSize(8);
  fmt.setAlphaBufferSize(8);
  fmt.setSamples(0);  // VTK renders into its own framebuffer; no multisampled default FBO
  QSurfaceFormat::setDefaultFormat(fmt);
}

VtkGlWidget::VtkGlWidget(QWidget* parent) : QOpenGLWidget(parent) {
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(true);
  setMinimumSize(200, 150);

  window_->SetOwnContext(false);
  window_->SetFrameBlitModeToNoBlit();  // paintGL() blits into Qt's framebuffer itself
  window_->SetMultiSamples(0);
  window_->AddRenderer(renderer_);

  callback_->SetClientData(this);
  callback_->SetCallback(&VtkGlWidget::onVtkEvent);
  window_->AddObserver(vtkCommand::WindowMakeCurrentEvent, callback_);
  window_->AddObserver(vtkCommand::WindowIsCurrentEvent, callback_);
  window_->AddObserver(vtkCommand::WindowSupportsOpenGLEvent, callback_);
  window_->AddObserver(vtkCommand::WindowIsDirectEvent, callback_);

  style_ = vtkSmartPointer<vtkInteractorStyleTrackballCamera>::New();
  interactor_->SetRenderWindow(window_);
  interactor_->SetInteractorStyle(style_);
  // The interactor never renders by itself: its render requests come back to us.
  interactor_->EnableRenderOff();
  interactor_->AddObserver(vtkCommand::RenderEvent, callback_);
  interactor_->Initialize();
}

VtkGlWidget::~VtkGlWidget() {
  // Release VTK's GL resources while our context can still be made current.
  if (glReady_) {
    makeCurrent();
    window_->Finalize();
    doneCurrent();
  }
  window_->RemoveObserver(callback_);
  interactor_->RemoveObserver(callback_);
}

vtkRenderer* VtkGlWidget::renderer() const {
  return renderer_;
}
vtkGenericOpenGLRenderWindow* VtkGlWidget::renderWindow() const {
  return window_;
}
vtkGenericRenderWindowInteractor* VtkGlWidget::interactor() const {
  return interactor_;
}

void VtkGlWidget::onVtkEvent(vtkObject*, unsigned long eventId, void* clientData, void* callData) {
  auto* self = static_cast<VtkGlWidget*>(clientData);
  switch (eventId) {
    case vtkCommand::WindowMakeCurrentEvent:
      if (self->context() && QOpenGLContext::currentContext() != self->context()) self->makeCurrent();
      break;
    case vtkCommand::WindowIsCurrentEvent:
      *static_cast<bool*>(callData) = self->context() != nullptr && QOpenGLContext::currentContext() == self->context();
      break;
    case vtkCommand::WindowSupportsOpenGLEvent:
      *static_cast<int*>(callData) = 1;
      break;
    case vtkCommand::WindowIsDirectEvent:
      *static_cast<int*>(callData) = 1;
      break;
    case vtkCommand::RenderEvent:
      if (!self->inPaint_) self->update();
      break;
    default:
      break;
  }
}

int VtkGlWidget::toPixels(double logical) const {
  return static_cast<int>(std::lround(logical * devicePixelRatioF()));
}

void VtkGlWidget::initializeGL() {
  window_->SetReadyForRendering(true);
  window_->SetIsCurrent(true);
  window_->OpenGLInitContext();
  window_->SetSize(toPixels(width()), toPixels(height()));
  interactor_->SetSize(toPixels(width()), toPixels(height()));
  glReady_ = true;
}

void VtkGlWidget::resizeGL(int w, int h) {
  window_->SetSize(toPixels(w), toPixels(h));
  interactor_->SetSize(toPixels(w), toPixels(h));
  interactor_->ConfigureEvent();
}

void VtkGlWidget::paintGL() {
  if (!glReady_) return;
  QElapsedTimer timer;
  timer.start();
  inPaint_ = true;
  const int w = toPixels(width()), h = toPixels(height());
  const int rw = std::clamp(static_cast<int>(std::lround(w * renderScale_)), 1, std::max(1, w));
  const int rh = std::clamp(static_cast<int>(std::lround(h * renderScale_)), 1, std::max(1, h));
  window_->SetSize(rw, rh);
  scaleLineWidths();
  window_->SetIsCurrent(true);
  window_->Render();
  // Copy VTK's display framebuffer into Qt's framebuffer object for this widget, magnified
  // (bilinear) when the frame was drawn at a reduced resolution.
  vtkOpenGLState* state = window_->GetState();
  state->PushFramebufferBindings();
  state->vtkglBindFramebuffer(0x8CA9 /*GL_DRAW_FRAMEBUFFER*/, defaultFramebufferObject());
  state->vtkglViewport(0, 0, w, h);
  state->vtkglScissor(0, 0, w, h);
  const bool reduced = rw != w || rh != h;
  window_->BlitDisplayFramebuffer(0, 0, 0, rw, rh, 0, 0, w, h, 0x00004000 /*GL_COLOR_BUFFER_BIT*/,
                                  reduced ? 0x2601 /*GL_LINEAR*/ : 0x2600 /*GL_NEAREST*/);
  state->PopFramebufferBindings();
  // Picking and display <-> world conversions between frames use the widget's resolution; the
  // framebuffers keep the reduced size until the next frame asks for another.
  window_->SetSize(w, h);
  lastRenderSize_ = QSize(rw, rh);
  inPaint_ = false;
  lastPaintMs_ = static_cast<double>(timer.nsecsElapsed()) * 1e-6;
}

double VtkGlWidget::clampRenderScale(double scale) {
  return std::clamp(std::isfinite(scale) ? scale : 1.0, 0.25, 1.0);
}

void VtkGlWidget::setRenderScale(double scale) {
  scale = clampRenderScale(scale);
  if (scale == renderScale_) return;
  renderScale_ = scale;
  // VTK sizes text in points at the window's DPI (72: one point a pixel), so text keeps its
  // size on screen after the magnification.
  window_->SetDPI(std::max(1, static_cast<int>(std::lround(72.0 * scale))));
  update();
}

namespace {
// The line width of a 3-D or 2-D actor's property (the two classes share no base that has it).
float lineWidthOf(vtkObject* property) {
  if (auto* p = vtkProperty::SafeDownCast(property)) return p->GetLineWidth();
  if (auto* p = vtkProperty2D::SafeDownCast(property)) return p->GetLineWidth();
  return 0.0f;
}
void setLineWidthOf(vtkObject* property, float width) {
  if (auto* p = vtkProperty::SafeDownCast(property)) p->SetLineWidth(width);
  if (auto* p = vtkProperty2D::SafeDownCast(property)) p->SetLineWidth(width);
}
}  // namespace

void VtkGlWidget::scaleLineWidths() {
  if (renderScale_ == 1.0) {
    for (auto& [key, e] : scaledWidths_)  // a width the application changed meanwhile stays
      if (lineWidthOf(e.property) == e.scaled) setLineWidthOf(e.property, e.original);
    scaledWidths_.clear();
    return;
  }
  const auto scale = static_cast<float>(renderScale_);
  auto apply = [&](vtkObject* property) {
    const float now = lineWidthOf(property);
    auto it = scaledWidths_.find(property);
    if (it != scaledWidths_.end() && it->second.scaled == now) return;  // already scaled
    const float scaled = std::min(now, std::max(1.0f, now * scale));    // never below 1 px
    scaledWidths_[property] = {property, now, scaled};
    if (scaled != now) setLineWidthOf(property, scaled);
  };
  vtkRendererCollection* renderers = window_->GetRenderers();
  renderers->InitTraversal();
  while (vtkRenderer* ren = renderers->GetNextItem()) {
    vtkActorCollection* actors = ren->GetActors();
    actors->InitTraversal();
    while (vtkActor* a = actors->GetNextActor()) apply(a->GetProperty());
    vtkActor2DCollection* overlays = ren->GetActors2D();
    overlays->InitTraversal();
    while (vtkActor2D* a = overlays->GetNextActor2D()) apply(a->GetProperty());
  }
}

QImage VtkGlWidget::renderToImage() {
  if (!isVisible()) return {};
  return grabFramebuffer();  // calls paintGL() into an offscreen FBO with our context
}

void VtkGlWidget::setEventPosition(const QPointF& pos, Qt::KeyboardModifiers mods, int repeat) {
  interactor_->SetSize(toPixels(width()), toPixels(height()));
  interactor_->SetEventInformationFlipY(toPixels(pos.x()), toPixels(pos.y()), (mods & Qt::ControlModifier) ? 1 : 0,
                                        (mods & Qt::ShiftModifier) ? 1 : 0, 0, repeat);
  interactor_->SetAltKey((mods & Qt::AltModifier) ? 1 : 0);
}

void VtkGlWidget::mousePressEvent(QMouseEvent* e) {
  setEventPosition(e->position(), e->modifiers());
  switch (e->button()) {
    case Qt::LeftButton:
      interactor_->InvokeEvent(vtkCommand::LeftButtonPressEvent);
      break;
    case Qt::MiddleButton:
      interactor_->InvokeEvent(vtkCommand::MiddleButtonPressEvent);
      break;
    case Qt::RightButton:
      interactor_->InvokeEvent(vtkCommand::RightButtonPressEvent);
      break;
    default:
      break;
  }
}

void VtkGlWidget::mouseDoubleClickEvent(QMouseEvent* e) {
  setEventPosition(e->position(), e->modifiers(), 1);
  if (e->button() == Qt::LeftButton) interactor_->InvokeEvent(vtkCommand::LeftButtonDoubleClickEvent);
}

void VtkGlWidget::mouseReleaseEvent(QMouseEvent* e) {
  setEventPosition(e->position(), e->modifiers());
  switch (e->button()) {
    case Qt::LeftButton:
      interactor_->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
      break;
    case Qt::MiddleButton:
      interactor_->InvokeEvent(vtkCommand::MiddleButtonReleaseEvent);
      break;
    case Qt::RightButton:
      interactor_->InvokeEvent(vtkCommand::RightButtonReleaseEvent);
      break;
    default:
      break;
  }
}

void VtkGlWidget::mouseMoveEvent(QMouseEvent* e) {
  setEventPosition(e->position(), e->modifiers());
  interactor_->InvokeEvent(vtkCommand::MouseMoveEvent);
}

void VtkGlWidget::wheelEvent(QWheelEvent* e) {
  setEventPosition(e->position(), e->modifiers());
  const int delta = e->angleDelta().y();
  if (delta > 0) interactor_->InvokeEvent(vtkCommand::MouseWheelForwardEvent);
  if (delta < 0) interactor_->InvokeEvent(vtkCommand::MouseWheelBackwardEvent);
  e->accept();
}

void VtkGlWidget::keyPressEvent(QKeyEvent* e) {
  // Only the trackball style's harmless keys reach VTK: r (reset camera), w / s (wireframe /
  // surface), f (fly to point). q / e would ask VTK to quit, 3 toggles stereo.
  const QString text = e->text().toLower();
  if (text.size() != 1 || !QStringLiteral("rwsf").contains(text)) {
    QOpenGLWidget::keyPressEvent(e);
    return;
  }
  const QPointF pos = mapFromGlobal(QCursor::pos());
  setEventPosition(pos, e->modifiers());
  const std::string sym = text.toStdString();
  interactor_->SetKeyEventInformation((e->modifiers() & Qt::ControlModifier) ? 1 : 0,
                                      (e->modifiers() & Qt::ShiftModifier) ? 1 : 0, sym[0], e->count(), sym.c_str());
  interactor_->InvokeEvent(vtkCommand::KeyPressEvent);
  interactor_->InvokeEvent(vtkCommand::CharEvent);
}

void VtkGlWidget::keyReleaseEvent(QKeyEvent* e) {
  const QString text = e->text().toLower();
  if (text.size() != 1 || !QStringLiteral("rwsf").contains(text)) {
    QOpenGLWidget::keyReleaseEvent(e);
    return;
  }
  interactor_->InvokeEvent(vtkCommand::KeyReleaseEvent);
}

void VtkGlWidget::enterEvent(QEnterEvent* e) {
  interactor_->InvokeEvent(vtkCommand::EnterEvent);
  QOpenGLWidget::enterEvent(e);
}

void VtkGlWidget::leaveEvent(QEvent* e) {
  interactor_->InvokeEvent(vtkCommand::LeaveEvent);
  QOpenGLWidget::leaveEvent(e);
}

}  // namespace fovea::viz
