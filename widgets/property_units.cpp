#include "widgets/property_units.h"

#include <QLocale>
#include <QRegularExpression>

namespace fovea::widgets {

namespace {

double convert(Quantity q, double v, const DisplayUnits& u, bool toShown) {
  switch (q) {
    case Quantity::Length:
      return toShown ? u.lengthFromMm(v) : u.lengthToMm(v);
    case Quantity::Angle:
      return toShown ? u.angleFromDeg(v) : u.angleToDeg(v);
    case Quantity::Other:
      break;
  }
  return v;
}

QVariant convertValue(const PropertySpec& spec, const QVariant& v, const DisplayUnits& u, bool toShown) {
  const Quantity q = quantityOf(spec);
  if (q == Quantity::Other || !v.isValid()) return v;
  if (spec.kind == PropertySpec::Kind::Number) return convert(q, v.toDouble(), u, toShown);
  if (spec.kind == PropertySpec::Kind::NumberList) {
    QVariantList out;
    for (const QVariant& x : v.toList()) out << convert(q, x.toDouble(), u, toShown);
    return out;
  }
  return v;
}

}  // namespace

Quantity quantityOf(const PropertySpec& spec) {
  if (spec.kind != PropertySpec::Kind::Number && spec.kind != PropertySpec::Kind::NumberList) return Quantity::Other;
  if (spec.unit == QLatin1String("mm")) return Quantity::Length;
  if (spec.unit == QLatin1String("deg")) return Quantity::Angle;
  return Quantity::Other;
}

PropertySpec displaySpec(const PropertySpec& spec, const DisplayUnits& u) {
  const Quantity q = quantityOf(spec);
  if (q == Quantity::Other) return spec;
  PropertySpec shown = spec;
  shown.unit = q == Quantity::Length ? u.lengthSymbol() : u.angleSymbol();
  // Every number of the range ("(0, 180)", "[-1e5, 1e5], != 0") converted: the conversions
  // are pure scalings, so bounds stay bounds and 0 stays 0.
  static const QRegularExpression number(R"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)");
  QString range;
  qsizetype last = 0;
  for (auto it = number.globalMatch(spec.range); it.hasNext();) {
    const auto m = it.next();
    range += spec.range.mid(last, m.capturedStart() - last);
    range += QString::number(convert(q, QLocale::c().toDouble(m.captured()), u, true), 'g', 6);
    last = m.capturedEnd();
  }
  shown.range = range + spec.range.mid(last);
  return shown;
}

QVariant toDisplay(const PropertySpec& spec, const QVariant& v, const DisplayUnits& u) {
  return convertValue(spec, v, u, true);
}

QVariant fromDisplay(const PropertySpec& spec, const QVariant& v, const DisplayUnits& u) {
  return convertValue(spec, v, u, false);
}

}  // namespace fovea::widgets
