#pragma once
// The editable properties of each scene element, generated from the scene field table
// (model/scene/scene_fields.h): label, group, unit, range and help as the table declares them
// (the rules themselves are applied by model validateScene), and how to read and write the
// value in a Scene. Keys are the paths in the scene file, as the loader's messages spell them
// ("hoe_layers[1].thickness_um", "projector.position_mm[0]"): one property per component.

#include <QString>
#include <QStringList>
#include <QVariant>

#include <functional>
#include <vector>

#include "model/scene/scene.h"

namespace fovea::widgets {

struct PropertySpec {
  enum class Kind { Number, Integer, Bool, Text, NumberList, Choice };
  QString key;
  QString group;  // heading in the editor ("Pose", "Recording", ...)
  QString label;
  QString unit;   // "mm", "deg", "nm", "µm", ...
  QString range;  // as the loader checks it: "> 0", "(5, 50)", "[1, 4]"
  QString help;   // what the value means (tooltip)
  Kind kind = Kind::Number;
  QStringList choices;  // Kind::Choice
  std::function<QVariant(const Scene&)> get;
  std::function<void(Scene&, const QVariant&)> set;
};

// The properties of element `id` (viz/scene_elements.h); empty for an unknown id.
std::vector<PropertySpec> propertiesOf(const Scene& scene, const QString& id);

// Text shown in an editor for a value of this spec ("25", "660, 532, 460").
QString formatValue(const PropertySpec& spec, const QVariant& value);
// Parses editor text into a value; on failure returns an invalid QVariant and sets `error`.
QVariant parseValue(const PropertySpec& spec, const QString& text, QString* error);

}  // namespace fovea::widgets
