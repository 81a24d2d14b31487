#pragma once
// Help ▸ User Guide and Help ▸ Keyboard Shortcuts. The guide is the README's studio section,
// compiled into the binary (resources.qrc) so the help shown is the help in the repository;
// the shortcut list is read from the window's menus and shortcuts when it is opened, so it
// lists the keys that work and cannot drift from them.

#include <QString>

class QMainWindow;
class QWidget;

namespace fovea::studio {

// The README's "## The studio" section (up to the next "## " heading), as Markdown, without
// its images (their files are not in the binary). Empty when the resource is missing.
QString userGuideMarkdown();

struct ShortcutEntry {
  QString where;  // "File", "View ▸ Panels", "3-D view"
  QString what;   // the action's text without its & mnemonic
  QString keys;   // in the platform's notation ("Ctrl+S"), several joined by ", "
};
// Every menu action with a shortcut and every QShortcut of the window, in menu order.
QList<ShortcutEntry> windowShortcuts(const QMainWindow* window);
QString shortcutsHtml(const QList<ShortcutEntry>& entries);

// Non-modal dialogs, one of each per window (shown again when already open).
void showUserGuide(QWidget* parent);
void showKeyboardShortcuts(QMainWindow* window);

}  // namespace fovea::studio
