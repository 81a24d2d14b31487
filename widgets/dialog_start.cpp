#include "widgets/dialog_start.h"

#include <QDir>
#include <QFileInfo>
#include <QSettings>
#include <QStringList>

#include "widgets/scene_document.h"

namespace fovea::widgets {

QString dialogStart(const SceneDocument* document, const QString& name) {
  if (!name.isEmpty() && QFileInfo(name).isAbsolute()) return name;
  QString folder;
  if (document && !document->filePath().isEmpty()) folder = QFileInfo(document->filePath()).absolutePath();
  if (folder.isEmpty()) {
    const QStringList recent = QSettings().value("recentFiles").toStringList();
    if (!recent.isEmpty() && QFileInfo(recent.front()).absoluteDir().exists())
      folder = QFileInfo(recent.front()).absolutePath();
  }
  if (folder.isEmpty()) folder = QDir::homePath();
  return name.isEmpty() ? folder : QDir(folder).filePath(name);
}

}  // namespace fovea::widgets
