#include "widgets/autosave.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QStandardPaths>

#include <algorithm>

#include "model/scene/scene_io.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

namespace {

bool writeAtomically(const QString& path, const QByteArray& bytes, QString* error) {
  QSaveFile out(path);
  if (!out.open(QIODevice::WriteOnly) || out.write(bytes) != bytes.size() || !out.commit()) {
    *error = out.errorString();
    out.cancelWriting();
    return false;
  }
  return true;
}

}  // namespace

Autosaver::Autosaver(SceneDocument* document, const QString& directory, QObject* parent)
    : QObject(parent), document_(document), directory_(directory) {
  QDir().mkpath(directory_);
  base_ = QDir(directory_)
              .filePath(QString("session-%1-%2")
                            .arg(QCoreApplication::applicationPid())
                            .arg(QDateTime::currentMSecsSinceEpoch()));
  lock_ = std::make_unique<QLockFile>(base_ + ".lock");
  lock_->setStaleLockTime(0);  // only a dead owner makes it stale, never its age
  if (!lock_->tryLock(0)) lastError_ = tr("cannot lock %1").arg(lock_->error());
  timer_.setSingleShot(true);
  connect(&timer_, &QTimer::timeout, this, [this] { saveNow(); });
  connect(document_, &SceneDocument::sceneChanged, this, &Autosaver::scheduleSave);
  connect(document_, &SceneDocument::modifiedChanged, this, [this](bool modified) {
    if (!modified) {  // saved, or undone back to the saved state
      timer_.stop();
      removeFiles();
    } else {
      scheduleSave();
    }
  });
  connect(document_, &SceneDocument::sceneReplaced, this, [this] {
    if (!document_->isModified()) removeFiles();
  });
}

Autosaver::~Autosaver() {
  removeFiles();
  if (lock_) lock_->unlock();
}

QString Autosaver::defaultDirectory() {
  const QString env = qEnvironmentVariable("FOVEA_RECOVERY_DIR");
  if (!env.isEmpty()) return env;
  return QDir(QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation)).filePath("recovery");
}

void Autosaver::setIntervalSeconds(int seconds) {
  intervalMs_ = std::clamp(seconds, 1, 600) * 1000;
  if (timer_.isActive()) timer_.start(intervalMs_);
}

void Autosaver::scheduleSave() {
  // The first unsaved change starts the clock; later edits do not push it back, so a long
  // editing session is still saved every interval.
  if (document_->isModified() && !timer_.isActive()) timer_.start(intervalMs_);
}

bool Autosaver::hasRecoveryFile() const {
  return QFileInfo::exists(recoveryFile());
}

bool Autosaver::saveNow() {
  timer_.stop();
  if (!document_->isModified()) {
    removeFiles();
    return true;
  }
  const std::string text = serializeScene(document_->scene());
  QJsonObject meta{{"original_path", document_->filePath()},
                   {"display_name", document_->displayName()},
                   {"scene_name", QString::fromStdString(document_->scene().name)},
                   {"saved_at", QDateTime::currentDateTimeUtc().toString(Qt::ISODateWithMs)},
                   {"pid", QCoreApplication::applicationPid()}};
  QString error;
  // Scene first, then its meta: a crash between the two leaves a scene without meta, which
  // findOrphans() still offers (under the scene file's own name).
  if (!writeAtomically(recoveryFile(), QByteArray::fromStdString(text), &error) ||
      !writeAtomically(base_ + ".meta.json", QJsonDocument(meta).toJson(), &error)) {
    lastError_ = tr("autosave to %1 failed: %2").arg(recoveryFile(), error);
    emit autosaveFailed(lastError_);
    return false;
  }
  emit autosaved(recoveryFile());
  return true;
}

void Autosaver::removeFiles() {
  QFile::remove(recoveryFile());
  QFile::remove(base_ + ".meta.json");
}

QList<RecoveryEntry> Autosaver::findOrphans(const QString& directory) {
  QList<RecoveryEntry> out;
  const QDir dir(directory);
  for (const QFileInfo& fi : dir.entryInfoList({"session-*.json"}, QDir::Files)) {
    if (fi.fileName().endsWith(".meta.json")) continue;
    const QString base = fi.absolutePath() + "/" + fi.completeBaseName();
    RecoveryEntry e;
    e.scenePath = fi.absoluteFilePath();
    e.metaPath = base + ".meta.json";
    e.lockPath = base + ".lock";
    // A lock held by a live studio (this one or another) means: not an orphan.
    QLockFile lock(e.lockPath);
    lock.setStaleLockTime(0);
    if (QFileInfo::exists(e.lockPath) && !lock.tryLock(0)) continue;
    lock.unlock();  // (tryLock removed a stale lock of a dead process)
    QFile metaFile(e.metaPath);
    if (metaFile.open(QIODevice::ReadOnly)) {
      const QJsonObject meta = QJsonDocument::fromJson(metaFile.readAll()).object();
      e.originalPath = meta.value("original_path").toString();
      e.displayName = meta.value("display_name").toString();
      e.sceneName = meta.value("scene_name").toString();
      e.savedAt = QDateTime::fromString(meta.value("saved_at").toString(), Qt::ISODateWithMs);
    }
    if (!e.savedAt.isValid()) e.savedAt = fi.lastModified();
    if (e.displayName.isEmpty()) e.displayName = fi.fileName();
    out << e;
  }
  std::sort(out.begin(), out.end(),
            [](const RecoveryEntry& a, const RecoveryEntry& b) { return a.savedAt > b.savedAt; });
  return out;
}

std::optional<Scene> Autosaver::loadEntry(const RecoveryEntry& entry, QString* error) {
  SceneLoadResult r = loadSceneFile(entry.scenePath.toStdString());
  if (!r.ok()) {
    if (error) {
      QStringList problems;
      for (const auto& e : r.errors) problems << QString::fromStdString(e);
      *error = problems.join('\n');
    }
    return std::nullopt;
  }
  return *r.scene;
}

void Autosaver::discard(const RecoveryEntry& entry) {
  QFile::remove(entry.scenePath);
  QFile::remove(entry.metaPath);
  QFile::remove(entry.lockPath);
}

}  // namespace fovea::widgets
