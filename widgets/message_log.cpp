#include "widgets/message_log.h"

#include <QTime>

namespace fovea::widgets {

MessageLog::MessageLog(QWidget* parent) : QPlainTextEdit(parent) {
  setReadOnly(true);
  setMaximumBlockCount(5000);
  // Long messages wrap at the dock's width: with no wrapping the view scrolled sideways to the
  // end of the newest line and every line seemed to start mid-word.
  setLineWrapMode(QPlainTextEdit::WidgetWidth);
  setWordWrapMode(QTextOption::WrapAtWordBoundaryOrAnywhere);
  QFont mono("monospace");
  mono.setStyleHint(QFont::Monospace);
  setFont(mono);
}

void MessageLog::add(Level level, const QString& message) {
  const char* tag = level == Level::Error ? "error" : level == Level::Warning ? "warning" : "info";
  const char* colour = level == Level::Error ? "#ff6060" : level == Level::Warning ? "#e0b040" : "#a0c0a0";
  entries_ << QStringLiteral("%1: %2").arg(tag, message);
  appendHtml(QStringLiteral("<span style='color:gray'>%1</span> <span style='color:%2'>%3</span> %4")
                 .arg(QTime::currentTime().toString("HH:mm:ss"), colour, tag, message.toHtmlEscaped()));
}

}  // namespace fovea::widgets
