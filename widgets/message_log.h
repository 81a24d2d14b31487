#pragma once
// The messages dock: time-stamped information, warnings and errors (load problems one per
// line, refused edits, saves). Read-only; entries() for tests.

#include <QPlainTextEdit>
#include <QStringList>

namespace fovea::widgets {

class MessageLog : public QPlainTextEdit {
  Q_OBJECT
 public:
  enum class Level { Info, Warning, Error };
  explicit MessageLog(QWidget* parent = nullptr);

  void add(Level level, const QString& message);
  void info(const QString& m) { add(Level::Info, m); }
  void warning(const QString& m) { add(Level::Warning, m); }
  void error(const QString& m) { add(Level::Error, m); }
  // Every message so far, "error: ..." / "warning: ..." / "info: ...".
  const QStringList& entries() const { return entries_; }

 private:
  QStringList entries_;
};

}  // namespace fovea::widgets
