#include "widgets/property_editor.h"

#include <QCheckBox>
#include <QComboBox>
#include <QEvent>
#include <QGridLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QLineEdit>
#include <QScrollArea>
#include <QVBoxLayout>

#include "model/scene/scene_fields.h"
#include "viz/scene_elements.h"
#include "widgets/property_units.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

using Kind = PropertySpec::Kind;

PropertyEditor::PropertyEditor(SceneDocument* document, QWidget* parent)
    : QWidget(parent), document_(document), units_(Preferences::instance().units()) {
  connect(&Preferences::instance(), &Preferences::changed, this, [this] { setUnits(Preferences::instance().units()); });
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);
  title_ = new QLabel(tr("Select an element in the scene tree or the 3D view."), this);
  title_->setWordWrap(true);
  QFont f = title_->font();
  f.setBold(true);
  title_->setFont(f);
  outer->addWidget(title_);
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setFocusPolicy(Qt::NoFocus);  // Tab goes to the fields, not to the frameless area
  form_ = new QWidget(scroll);
  grid_ = new QGridLayout(form_);
  grid_->setColumnStretch(1, 1);
  grid_->setAlignment(Qt::AlignTop);
  scroll->setWidget(form_);
  outer->addWidget(scroll, 1);

  connect(document_, &SceneDocument::sceneChanged, this, [this] {
    const auto specs = propertiesOf(document_->scene(), element_);
    bool same = specs.size() == rows_.size();
    for (std::size_t i = 0; same && i < specs.size(); ++i) same = specs[i].key == rows_[i].spec.key;
    if (!same)
      rebuild();
    else
      refreshValues();
  });
}

void PropertyEditor::setUnits(const DisplayUnits& units) {
  if (units == units_) return;
  units_ = units;
  rebuild();
}

QString PropertyEditor::unitFor(const QString& key) const {
  for (const auto& r : rows_)
    if (r.spec.key == key) return r.unit ? r.unit->text() : QString();
  return {};
}

void PropertyEditor::showElement(const QString& id) {
  if (id == element_ && !rows_.empty()) return;
  element_ = id;
  rebuild();
}

void PropertyEditor::rebuild() {
  for (auto& r : rows_) {
    delete r.field;
    delete r.message;
    delete r.unit;
  }
  rows_.clear();
  while (QLayoutItem* item = grid_->takeAt(0)) {
    delete item->widget();
    delete item;
  }
  const Scene& scene = document_->scene();
  std::vector<PropertySpec> specs = propertiesOf(scene, element_);
  title_->setText(specs.empty() ? tr("Select an element in the scene tree or the 3D view.")
                                : viz::elementTitle(scene, element_));
  int gridRow = 0;
  QString group;
  rows_.reserve(specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const PropertySpec spec = displaySpec(specs[i], units_);  // unit and range as shown
    if (spec.group != group) {
      group = spec.group;
      auto* heading = new QLabel("<b>" + group.toHtmlEscaped() + "</b>", form_);
      grid_->addWidget(heading, gridRow++, 0, 1, 3);
    }
    auto* label = new QLabel(spec.label, form_);
    const QString tip = (spec.help.isEmpty() ? "" : spec.help + "\n") + spec.key +
                        (spec.unit.isEmpty() ? "" : " [" + spec.unit + "]") +
                        (spec.range.isEmpty() ? "" : "\nrange: " + spec.range);
    label->setToolTip(tip);
    QWidget* field = nullptr;
    const int row = static_cast<int>(i);
    switch (spec.kind) {
      case Kind::Bool: {
        auto* box = new QCheckBox(form_);
        connect(box, &QCheckBox::toggled, this, [this, row](bool on) { commit(row, on); });
        field = box;
        break;
      }
      case Kind::Choice: {
        auto* combo = new QComboBox(form_);
        combo->addItems(spec.choices);
        connect(combo, &QComboBox::textActivated, this, [this, row](const QString& t) { commit(row, t); });
        field = combo;
        break;
      }
      default: {
        auto* edit = new QLineEdit(form_);
        if (!spec.range.isEmpty()) edit->setPlaceholderText(spec.range);
        connect(edit, &QLineEdit::editingFinished, this, [this, row, edit] {
          if (!edit->isModified()) return;
          edit->setModified(false);
          const QString key = rows_[static_cast<std::size_t>(row)].spec.key;
          // Refused as the focus left the field (Tab, a click elsewhere): the field shows the
          // model's value again, the refusal stays written under it.
          if (!commitText(key, edit->text()).isEmpty() && !edit->hasFocus()) revert(key, true);
        });
        edit->installEventFilter(this);
        field = edit;
        break;
      }
    }
    field->setToolTip(tip);
    field->setObjectName(spec.key);
    auto* unit = new QLabel(spec.unit, form_);
    auto* message = new QLabel(form_);
    message->setWordWrap(true);
    message->setStyleSheet("color: #e04040;");
    message->setVisible(false);
    grid_->addWidget(label, gridRow, 0);
    grid_->addWidget(field, gridRow, 1);
    grid_->addWidget(unit, gridRow++, 2);
    grid_->addWidget(message, gridRow++, 0, 1, 3);
    rows_.push_back({specs[i], field, message, unit});
  }
  refreshValues();
}

void PropertyEditor::refreshValues() {
  const Scene& scene = document_->scene();
  title_->setText(rows_.empty() ? title_->text() : viz::elementTitle(scene, element_));
  for (auto& r : rows_) {
    const QVariant v = r.spec.get(scene);
    if (auto* box = qobject_cast<QCheckBox*>(r.field)) {
      QSignalBlocker block(box);
      box->setChecked(v.toBool());
    } else if (auto* combo = qobject_cast<QComboBox*>(r.field)) {
      QSignalBlocker block(combo);
      combo->setCurrentText(v.toString());
    } else if (auto* edit = qobject_cast<QLineEdit*>(r.field)) {
      edit->setText(formatValue(r.spec, toDisplay(r.spec, v, units_)));
      edit->setModified(false);
    }
    setMessage(r, {});
  }
}

bool PropertyEditor::eventFilter(QObject* watched, QEvent* event) {
  auto* edit = qobject_cast<QLineEdit*>(watched);
  if (!edit) return QWidget::eventFilter(watched, event);
  const bool esc = (event->type() == QEvent::KeyPress || event->type() == QEvent::ShortcutOverride) &&
                   static_cast<QKeyEvent*>(event)->key() == Qt::Key_Escape;
  for (auto& r : rows_) {
    if (r.field != edit) continue;
    const bool refused = r.refused;
    // Esc: the typing (or a refused value) is dropped and the model's value comes back. The
    // override is taken only then, so Esc stays the e-stop everywhere else.
    if (esc && (edit->isModified() || refused)) {
      event->accept();
      if (event->type() == QEvent::KeyPress) revert(r.spec.key, false);
      return true;
    }
    // The focus leaves a field that still shows a refused value: back to the model's value.
    if (event->type() == QEvent::FocusOut && refused && !edit->isModified()) revert(r.spec.key, true);
    break;
  }
  return QWidget::eventFilter(watched, event);
}

void PropertyEditor::revert(const QString& key, bool keepMessage) {
  for (auto& r : rows_) {
    if (r.spec.key != key) continue;
    const QString why = r.message->text();
    if (auto* edit = qobject_cast<QLineEdit*>(r.field)) {
      const QString shown = formatValue(r.spec, toDisplay(r.spec, r.spec.get(document_->scene()), units_));
      edit->setText(shown);
      edit->setModified(false);
      setMessage(r, {});
      // Kept as a note (not red: the field's value is the model's again).
      if (keepMessage && !why.isEmpty()) {
        r.message->setText(
            tr("%1 (kept %2)")
                .arg(why, shown + (r.unit && !r.unit->text().isEmpty() ? " " + r.unit->text() : QString())));
        r.message->setVisible(true);
      }
    }
    return;
  }
}

void PropertyEditor::setMessage(Row& r, const QString& message) {
  r.refused = !message.isEmpty();
  r.message->setText(message);
  r.message->setVisible(!message.isEmpty());
  r.field->setStyleSheet(message.isEmpty() ? QString() : QStringLiteral("background: #5a2020; color: white;"));
}

QWidget* PropertyEditor::fieldFor(const QString& key) const {
  for (const auto& r : rows_)
    if (r.spec.key == key) return r.field;
  return nullptr;
}

QString PropertyEditor::messageFor(const QString& key) const {
  for (const auto& r : rows_)
    if (r.spec.key == key) return r.message->text();
  return {};
}

QString PropertyEditor::commitText(const QString& key, const QString& text) {
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    if (rows_[i].spec.key != key) continue;
    if (auto* edit = qobject_cast<QLineEdit*>(rows_[i].field)) edit->setText(text);
    QString error;
    const QVariant shown = parseValue(rows_[i].spec, text, &error);
    if (!shown.isValid()) {
      setMessage(rows_[i], error);
      emit editRefused(key, error);
      return error;
    }
    commit(static_cast<int>(i), fromDisplay(rows_[i].spec, shown, units_));
    return rows_.size() > i ? messageFor(key) : QString();
  }
  return tr("no property %1").arg(key);
}

void PropertyEditor::commit(int index, const QVariant& value) {
  Row& r = rows_[static_cast<std::size_t>(index)];
  const PropertySpec spec = r.spec;  // the rows may be rebuilt by the edit
  const PropertySpec shown = displaySpec(spec, units_);
  const QString text = tr("Set %1 to %2%3")
                           .arg(spec.label.toLower(), formatValue(shown, toDisplay(spec, value, units_)),
                                shown.unit.isEmpty() ? "" : " " + shown.unit);
  const QStringList problems = document_->applyEdit(text, [&spec, &value](Scene& s) { spec.set(s, value); });
  if (problems.isEmpty()) return;
  QStringList named;  // "hoe_layers[1].thickness_um: ..." -> "Thickness: ...": the label the user sees
  for (const QString& p : problems) {
    const qsizetype colon = p.indexOf(QLatin1String(": "));
    const std::string label = colon < 0 ? std::string() : fieldLabel(document_->scene(), p.left(colon).toStdString());
    named << (label.empty() ? p : QString::fromStdString(label) + p.mid(colon));
  }
  // Refused: the model is unchanged; show why next to the field.
  for (auto& row : rows_) {
    if (row.spec.key != spec.key) continue;
    const QString message = named.join('\n');
    setMessage(row, message);
    if (auto* box = qobject_cast<QCheckBox*>(row.field)) {
      QSignalBlocker block(box);
      box->setChecked(spec.get(document_->scene()).toBool());
    } else if (auto* combo = qobject_cast<QComboBox*>(row.field)) {
      QSignalBlocker block(combo);
      combo->setCurrentText(spec.get(document_->scene()).toString());
    }
    emit editRefused(spec.key, message);
  }
}

}  // namespace fovea::widgets
