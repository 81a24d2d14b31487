#pragma once
// Where a file dialog opens: in the current scene's folder, not in the process's working
// directory. For a scene not saved yet, the folder of the last scene opened or saved
// (QSettings "recentFiles"), else the home folder.

#include <QString>

namespace fovea::widgets {

class SceneDocument;

// `name` empty: the folder. A relative `name` (a suggested file name, a path typed relative
// to the scene): that name in the folder. An absolute `name` is returned as it is.
QString dialogStart(const SceneDocument* document, const QString& name = {});

}  // namespace fovea::widgets
