#pragma once
// Never lose work: while the open scene has unsaved changes, it is written every few seconds
// to a recovery file (a plain scene file, loadable by any tool, plus a small .meta.json with
// where it came from). Each running studio owns its files through a QLockFile; a clean exit,
// a save, or undoing back to the saved state removes them. Files whose lock is not held any
// more (the studio crashed or was killed) are offered for recovery on the next start.
//
// Layout of the recovery directory (default <AppLocalData>/recovery, or $FOVEA_RECOVERY_DIR):
//   session-<pid>-<ms>.json        the scene (serializeScene)
//   session-<pid>-<ms>.meta.json   {"original_path", "display_name", "saved_at", "pid", "scene_name"}
//   session-<pid>-<ms>.lock        held while that studio runs

#include <QDateTime>
#include <QList>
#include <QLockFile>
#include <QObject>
#include <QString>
#include <QStringList>
#include <QTimer>

#include <memory>
#include <optional>

#include "model/scene/scene.h"

namespace fovea::widgets {

class SceneDocument;

struct RecoveryEntry {
  QString scenePath, metaPath, lockPath;
  QString originalPath;  // empty: the scene had never been saved
  QString displayName;
  QString sceneName;
  QDateTime savedAt;
};

class Autosaver : public QObject {
  Q_OBJECT
 public:
  // Starts a session in `directory` (created if needed).
  Autosaver(SceneDocument* document, const QString& directory, QObject* parent = nullptr);
  ~Autosaver() override;  // a clean end: removes this session's files

  static QString defaultDirectory();

  void setIntervalSeconds(int seconds);
  int intervalSeconds() const { return intervalMs_ / 1000; }
  // Writes the recovery file now when the scene has unsaved changes, else removes it.
  bool saveNow();
  QString recoveryFile() const { return base_ + ".json"; }
  bool hasRecoveryFile() const;
  QString lastError() const { return lastError_; }

  // Recovery files of studios that are not running any more (no lock file, or a lock whose
  // owner process is gone), newest first.
  static QList<RecoveryEntry> findOrphans(const QString& directory);
  // Loads an entry's scene; empty with `error` set when it is unreadable or invalid.
  static std::optional<Scene> loadEntry(const RecoveryEntry& entry, QString* error = nullptr);
  // Removes an entry's files.
  static void discard(const RecoveryEntry& entry);

 signals:
  void autosaved(const QString& path);
  void autosaveFailed(const QString& message);

 private:
  void scheduleSave();
  void removeFiles();

  SceneDocument* document_;
  QString directory_;
  QString base_;
  std::unique_ptr<QLockFile> lock_;
  QTimer timer_;
  int intervalMs_ = 5000;
  QString lastError_;
};

}  // namespace fovea::widgets
