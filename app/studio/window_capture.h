#pragma once
// A picture of a whole window as the user sees it: QWidget::grab() of the window with the
// OpenGL content of every visible QOpenGLWidget (our VTK views) painted over its place, so
// the 3D view is never black or stale in screenshots.

#include <QImage>

class QWidget;

namespace fovea::studio {

QImage captureWithOpenGl(QWidget* window);

// A QOpenGLWidget's framebuffer grab as the screen shows it, opaque (Format_RGB32). Qt hands
// the framebuffer over as premultiplied RGBA, but its colours are already blended over the
// view's background and the screen ignores its alpha (below 1 where text and translucent
// passes drew). Converting to RGB32 would divide the colours by that alpha: the labels' dark
// boxes (55 % opacity) came out light. This keeps the colours and sets alpha to 1.
QImage opaqueFramebuffer(const QImage& grab);

// Parses "1600x1000" (each 64..8192); false on anything else.
bool parseWindowSize(const QString& text, QSize* size);

}  // namespace fovea::studio
