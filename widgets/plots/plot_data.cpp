#include "widgets/plots/plot_data.h"

namespace fovea::widgets {

namespace {

QString csvField(const QVariant& v) {
  if (!v.isValid() || v.isNull()) return {};
  const int t = v.typeId();
  if (t == QMetaType::Double || t == QMetaType::Float) return QString::number(v.toDouble(), 'g', 10);
  if (t == QMetaType::Int || t == QMetaType::LongLong || t == QMetaType::UInt) return QString::number(v.toLongLong());
  if (t == QMetaType::Bool) return v.toBool() ? QStringLiteral("true") : QStringLiteral("false");
  QString s = v.toString();
  if (s.contains(',') || s.contains('"') || s.contains('\n') || s.contains('\r'))
    s = '"' + s.replace('"', QStringLiteral("\"\"")) + '"';
  return s;
}

}  // namespace

QString plotCsv(const PlotData& plot) {
  QString out;
  QStringList header;
  for (const QString& c : plot.columns) header << csvField(c);
  out += header.join(',') + "\r\n";
  for (const QVariantList& row : plot.rows) {
    QStringList cells;
    for (const QVariant& v : row) cells << csvField(v);
    out += cells.join(',') + "\r\n";
  }
  return out;
}

}  // namespace fovea::widgets
