#include "widgets/scene_properties.h"

#include <QLocale>

#include <algorithm>

#include "model/scene/scene_fields.h"
#include "model/scene/scene_io.h"

namespace fovea::widgets {

namespace {

using Kind = PropertySpec::Kind;

Kind kindOf(const FieldInfo& f) {
  switch (f.type) {
    case FieldType::Integer:
    case FieldType::Integers:
      return Kind::Integer;
    case FieldType::Bool:
      return Kind::Bool;
    case FieldType::Text:
      return f.choices.empty() ? Kind::Text : Kind::Choice;
    case FieldType::NumberList:
      return Kind::NumberList;
    default:
      return Kind::Number;
  }
}

// The value of component `k` (-1: the whole field) as a QVariant, and back.
QVariant read(const ValueRef& ref, int k) {
  const auto i = static_cast<std::size_t>(k < 0 ? 0 : k);
  if (auto* d = std::get_if<double*>(&ref)) return **d;
  if (auto* n = std::get_if<int*>(&ref)) return **n;
  if (auto* b = std::get_if<bool*>(&ref)) return **b;
  if (auto* t = std::get_if<std::string*>(&ref)) return QString::fromStdString(**t);
  if (auto* a = std::get_if<std::span<double>>(&ref)) return (*a)[i];
  if (auto* a = std::get_if<std::span<int>>(&ref)) return (*a)[i];
  QVariantList list;
  for (double d : *std::get<std::vector<double>*>(ref)) list << d;
  return list;
}

void write(const ValueRef& ref, int k, const QVariant& v) {
  const auto i = static_cast<std::size_t>(k < 0 ? 0 : k);
  if (auto* d = std::get_if<double*>(&ref)) **d = v.toDouble();
  if (auto* n = std::get_if<int*>(&ref)) **n = v.toInt();
  if (auto* b = std::get_if<bool*>(&ref)) **b = v.toBool();
  if (auto* t = std::get_if<std::string*>(&ref)) **t = v.toString().toStdString();
  if (auto* a = std::get_if<std::span<double>>(&ref)) (*a)[i] = v.toDouble();
  if (auto* a = std::get_if<std::span<int>>(&ref)) (*a)[i] = v.toInt();
  if (auto* l = std::get_if<std::vector<double>*>(&ref)) {
    std::vector<double> d;
    for (const auto& x : v.toList()) d.push_back(x.toDouble());
    **l = d;
  }
}

PropertySpec specOf(const SceneField& f, int k) {
  const FieldInfo& info = *f.info;
  PropertySpec p;
  p.key = QString::fromStdString(f.path) + (k < 0 ? QString() : QStringLiteral("[%1]").arg(k));
  p.group = QString::fromStdString(info.group);
  p.label = QString::fromStdString(info.label(static_cast<std::size_t>(k < 0 ? 0 : k)));
  p.unit = QString::fromStdString(f.unit);
  p.range = QString::fromStdString(info.rangeText());
  p.help = QString::fromStdString(info.help);
  p.kind = kindOf(info);
  for (const auto& c : info.choices) p.choices << QString::fromStdString(c);
  p.get = [ref = f.ref, k](const Scene& s) { return read(ref(const_cast<Scene&>(s)), k); };  // only read
  p.set = [ref = f.ref, k](Scene& s, const QVariant& v) { write(ref(s), k, v); };
  return p;
}

}  // namespace

std::vector<PropertySpec> propertiesOf(const Scene& scene, const QString& id) {
  std::vector<PropertySpec> specs;
  for (const SceneField& f : elementFields(scene, id.toStdString())) {
    const bool fixed_array = f.info->type == FieldType::Numbers || f.info->type == FieldType::Integers;
    if (!fixed_array) {
      specs.push_back(specOf(f, -1));
      continue;
    }
    for (std::size_t k = 0; k < f.info->size; ++k) specs.push_back(specOf(f, static_cast<int>(k)));
  }
  // One heading per group, in the order the groups first appear in the table.
  QStringList groups;
  for (const auto& p : specs)
    if (!groups.contains(p.group)) groups << p.group;
  std::stable_sort(specs.begin(), specs.end(), [&groups](const PropertySpec& a, const PropertySpec& b) {
    return groups.indexOf(a.group) < groups.indexOf(b.group);
  });
  return specs;
}

QString formatValue(const PropertySpec& spec, const QVariant& value) {
  switch (spec.kind) {
    case Kind::Number:
      return QString::fromStdString(formatNumber(value.toDouble()));
    case Kind::Integer:
      return QString::number(value.toInt());
    case Kind::Bool:
      return value.toBool() ? "true" : "false";
    case Kind::NumberList: {
      QStringList parts;
      for (const auto& v : value.toList()) parts << QString::fromStdString(formatNumber(v.toDouble()));
      return parts.join(", ");
    }
    case Kind::Text:
    case Kind::Choice:
      return value.toString();
  }
  return {};
}

QVariant parseValue(const PropertySpec& spec, const QString& raw, QString* error) {
  const QString text = raw.trimmed();
  const QLocale c = QLocale::c();
  bool ok = false;
  switch (spec.kind) {
    case Kind::Number: {
      const double d = c.toDouble(text, &ok);
      if (!ok) {
        *error = QStringLiteral("%1: not a number: \"%2\"").arg(spec.label, text);
        return {};
      }
      return d;
    }
    case Kind::Integer: {
      const int i = c.toInt(text, &ok);
      if (!ok) {
        *error = QStringLiteral("%1: not an integer: \"%2\"").arg(spec.label, text);
        return {};
      }
      return i;
    }
    case Kind::NumberList: {
      QVariantList list;
      for (const QString& part : text.split(',', Qt::SkipEmptyParts)) {
        const double d = c.toDouble(part.trimmed(), &ok);
        if (!ok) {
          *error = QStringLiteral("%1: not a number: \"%2\"").arg(spec.label, part.trimmed());
          return {};
        }
        list << d;
      }
      return list;
    }
    case Kind::Bool:
      return text == "true";
    case Kind::Text:
    case Kind::Choice:
      return text;
  }
  return {};
}

}  // namespace fovea::widgets
