#include "app/studio/help_dialogs.h"

#include <QAction>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFile>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QRegularExpression>
#include <QShortcut>
#include <QTextBrowser>
#include <QVBoxLayout>

namespace fovea::studio {

namespace {

QString plainText(QString text) {
  text = text.section('\t', 0, 0);
  text.remove(QRegularExpression("&(?=[^&])"));
  text.replace("&&", "&");
  return text.remove(QStringLiteral("…")).trimmed();
}

QString keysOf(const QAction* a) {
  QStringList keys;
  for (const QKeySequence& k : a->shortcuts()) keys << k.toString(QKeySequence::NativeText);
  // A key the menu only shows (text "Emergency Stop\tEsc": the key is a QShortcut elsewhere).
  if (keys.isEmpty() && a->text().contains('\t')) keys << a->text().section('\t', 1);
  return keys.join(", ");
}

void collect(const QMenu* menu, const QString& where, QList<ShortcutEntry>& out) {
  for (const QAction* a : menu->actions()) {
    if (a->isSeparator()) continue;
    if (const QMenu* sub = a->menu()) {
      collect(sub, where + " ▸ " + plainText(sub->title()), out);
      continue;
    }
    const QString keys = keysOf(a);
    if (!keys.isEmpty()) out.push_back({where, plainText(a->text()), keys});
  }
}

QDialog* helpDialog(QWidget* parent, const QString& objectName, const QString& title, QTextBrowser** browser) {
  if (auto* open = parent->findChild<QDialog*>(objectName)) {
    *browser = open->findChild<QTextBrowser*>();
    return open;
  }
  auto* d = new QDialog(parent);
  d->setObjectName(objectName);
  d->setWindowTitle(title);
  auto* layout = new QVBoxLayout(d);
  *browser = new QTextBrowser(d);
  (*browser)->setOpenExternalLinks(true);
  layout->addWidget(*browser);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, d);
  QObject::connect(buttons, &QDialogButtonBox::rejected, d, &QDialog::close);
  layout->addWidget(buttons);
  // Most of a small screen, never more than it has.
  d->resize(std::min(860, parent->width() * 9 / 10), std::min(700, parent->height() * 9 / 10));
  return d;
}

}  // namespace

QString userGuideMarkdown() {
  QFile f(":/help/README.md");
  if (!f.open(QIODevice::ReadOnly)) return {};
  const QString readme = QString::fromUtf8(f.readAll());
  const qsizetype start = readme.indexOf("\n## The studio");
  if (start < 0) return {};
  const qsizetype end = readme.indexOf("\n## ", start + 4);
  QString section = readme.mid(start + 1, end < 0 ? -1 : end - start - 1);
  section.remove(QRegularExpression("!\\[[^\\]]*\\]\\([^)]*\\)\\n?"));  // images: not shipped
  // Links into docs/ point at the installed copies' names; keep their text only.
  section.replace(QRegularExpression("\\[([^\\]]+)\\]\\((docs/[^)]*)\\)"), "\\1 (\\2)");
  return "# Foveated AR Studio — user guide\n\n" + section;
}

QList<ShortcutEntry> windowShortcuts(const QMainWindow* window) {
  QList<ShortcutEntry> out;
  for (const QAction* a : window->menuBar()->actions())
    if (const QMenu* m = a->menu()) collect(m, plainText(m->title()), out);
  for (const QShortcut* s : window->findChildren<QShortcut*>()) {
    if (s->key().isEmpty() || !s->isEnabled()) continue;
    const QWidget* owner = qobject_cast<const QWidget*>(s->parent());
    const QString where = s->property("where").toString().isEmpty()
                              ? (owner && !owner->windowTitle().isEmpty() ? owner->windowTitle() : QString("Window"))
                              : s->property("where").toString();
    out.push_back({where, s->whatsThis().isEmpty() ? s->objectName() : s->whatsThis(),
                   s->key().toString(QKeySequence::NativeText)});
  }
  return out;
}

QString shortcutsHtml(const QList<ShortcutEntry>& entries) {
  QString h =
      "<table border='0' cellspacing='0' cellpadding='4'><tr><th align='left'>Key</th>"
      "<th align='left'>Does</th><th align='left'>Where</th></tr>";
  for (const ShortcutEntry& e : entries)
    h += QString("<tr><td><b>%1</b></td><td>%2</td><td>%3</td></tr>")
             .arg(e.keys.toHtmlEscaped(), e.what.toHtmlEscaped(), e.where.toHtmlEscaped());
  return h + "</table>";
}

void showUserGuide(QWidget* parent) {
  QTextBrowser* browser = nullptr;
  QDialog* d = helpDialog(parent, "userGuideDialog", QObject::tr("User Guide"), &browser);
  const QString md = userGuideMarkdown();
  browser->setMarkdown(md.isEmpty() ? QObject::tr("The user guide is missing from this build.") : md);
  d->show();
  d->raise();
}

void showKeyboardShortcuts(QMainWindow* window) {
  QTextBrowser* browser = nullptr;
  QDialog* d = helpDialog(window, "shortcutsDialog", QObject::tr("Keyboard Shortcuts"), &browser);
  browser->setHtml("<h3>" + QObject::tr("Keyboard shortcuts") + "</h3>" + shortcutsHtml(windowShortcuts(window)) +
                   "<p>" +
                   QObject::tr("Tab and Shift+Tab move the focus between fields; the mouse wheel changes a spin box, "
                               "list or slider only while it has the focus.") +
                   "</p>");
  d->show();
  d->raise();
}

}  // namespace fovea::studio
