#pragma once
// Property editor of the selected scene element: one typed field per property with its
// unit and range. A value is applied when editing finishes, through SceneDocument::applyEdit
// (an undoable command); a value the scene rules refuse stays in the field, marked red, with
// the rule's message shown under it, and the model is left unchanged. Esc, or the focus
// leaving the field, puts the model's value back in it (the refusal stays as a note).
// Lengths (mm) and angles (deg) are shown and typed in the preferred display units
// (Preferences, property_units.h) and converted back to mm / deg on edit; changing the
// preference updates the open editor.

#include <QHash>
#include <QPointer>
#include <QWidget>

#include <vector>

#include "widgets/preferences.h"
#include "widgets/scene_properties.h"

class QGridLayout;
class QLabel;

namespace fovea::widgets {

class SceneDocument;

class PropertyEditor : public QWidget {
  Q_OBJECT
 public:
  explicit PropertyEditor(SceneDocument* document, QWidget* parent = nullptr);

  void showElement(const QString& id);
  const QString& element() const { return element_; }

  // For tests and scripting: the field of a property key, and its current message.
  QWidget* fieldFor(const QString& key) const;
  QString messageFor(const QString& key) const;
  // Commits `text` (in the display units) to the property as if typed and confirmed; returns
  // the refusal (or empty).
  QString commitText(const QString& key, const QString& text);
  // The units the fields show (default: the preferences'; follows Preferences::changed).
  void setUnits(const DisplayUnits& units);
  const DisplayUnits& units() const { return units_; }
  // The unit label shown next to a property's field.
  QString unitFor(const QString& key) const;

 signals:
  void editRefused(const QString& key, const QString& message);

 private:
  struct Row {
    PropertySpec spec;  // in the model's units
    QPointer<QWidget> field;
    QPointer<QLabel> message;
    QPointer<QLabel> unit;
    bool refused = false;  // the field shows a value the model refused
  };
  void rebuild();
  void refreshValues();
  void commit(int row, const QVariant& value);
  void setMessage(Row& row, const QString& message);
  // The field of `key` shows the model's value again; `keepMessage`: the refusal stays as a note.
  void revert(const QString& key, bool keepMessage);
  bool eventFilter(QObject* watched, QEvent* event) override;

  SceneDocument* document_;
  QString element_;
  QLabel* title_ = nullptr;
  QWidget* form_ = nullptr;
  QGridLayout* grid_ = nullptr;
  std::vector<Row> rows_;
  DisplayUnits units_;
};

}  // namespace fovea::widgets
