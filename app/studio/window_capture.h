#pragma once
// A picture of a whole window as the user sees it: QWidget::grab() of the window with the
// OpenGL content of every visible QOpenGLWidget (our VTK views) painted over its place, so
// the 3D view is never black or stale in screenshots.

#include <QImage>

class QWidget;

namespace fovea::studio {

QImage captureWithOpenGl(QWidget* window);

// Parses "1600x1000" (each 64..8192); false on anything else.
bool parseWindowSize(const QString& text, QSize* size);

}  // namespace fovea::studio
