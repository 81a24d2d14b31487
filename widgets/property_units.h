#pragma once
// The property editor's display units: a property the model keeps in mm (unit "mm") is shown
// and typed in the preferred length unit, one in degrees (unit "deg") in the preferred angle
// unit (widgets/preferences.h DisplayUnits); every other unit is shown as is. The model
// always receives mm and degrees; the range shown is converted with the value.

#include <QString>
#include <QVariant>

#include "widgets/preferences.h"
#include "widgets/scene_properties.h"

namespace fovea::widgets {

enum class Quantity { Other, Length, Angle };

// What a property measures, by its model unit.
Quantity quantityOf(const PropertySpec& spec);
// The spec as shown: unit symbol and range in the display units (key, get, set unchanged).
PropertySpec displaySpec(const PropertySpec& spec, const DisplayUnits& units);
// A model value (number or number list) in the display units, and back.
QVariant toDisplay(const PropertySpec& spec, const QVariant& modelValue, const DisplayUnits& units);
QVariant fromDisplay(const PropertySpec& spec, const QVariant& shownValue, const DisplayUnits& units);

}  // namespace fovea::widgets
