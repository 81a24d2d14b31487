#include "viz/scene_elements.h"

#include <QRegularExpression>

#include "model/scene/scene_io.h"

namespace fovea::viz {

QString hoeLayerId(int index) {
  return QStringLiteral("hoe_layers[%1]").arg(index);
}
QString stageId(int index) {
  return QStringLiteral("stages[%1]").arg(index);
}

int indexedElement(const QString& id, const QString& prefix) {
  const QRegularExpression re("^" + QRegularExpression::escape(prefix) + "\\[(\\d+)\\]$");
  const auto m = re.match(id);
  return m.hasMatch() ? m.captured(1).toInt() : -1;
}

QStringList elementIds(const Scene& scene) {
  QStringList ids{"projector", "hoe"};
  for (int i = 0; i < static_cast<int>(scene.hoe_layers.size()); ++i) ids << hoeLayerId(i);
  ids << "eye"
      << "foveal_display"
      << "beam_shaping_lens"
      << "foveation";
  for (int i = 0; i < static_cast<int>(scene.stages.size()); ++i) ids << stageId(i);
  if (scene.binocular) ids << "binocular";  // the two-eye block (its fields: mode, IPD)
  return ids;
}

QString elementTitle(const Scene& scene, const QString& id) {
  auto q = [](const std::string& s) { return QString::fromStdString(s); };
  if (id == "projector") return "Projector — " + q(scene.projector.name);
  if (id == "hoe") return "HOE — " + q(scene.hoe.name);
  if (id == "eye") return QStringLiteral("Eye");
  if (id == "foveal_display") return "Foveal display — " + q(scene.foveal_display.name);
  if (id == "beam_shaping_lens")
    return "Beam-shaping lens — " + q(scene.lens.name) + (scene.lens.enabled ? "" : " (disabled)");
  if (id == "foveation") return QStringLiteral("Foveation blend");
  if (id == "binocular" && scene.binocular)
    return "Binocular — " + q(scene.binocular->mode) + ", IPD " + q(formatNumber(scene.binocular->ipd_mm)) + " mm";
  if (int i = indexedElement(id, "hoe_layers"); i >= 0 && i < static_cast<int>(scene.hoe_layers.size())) {
    const auto& l = scene.hoe_layers[static_cast<std::size_t>(i)];
    return QStringLiteral("Layer %1 (%2, %3 nm)")
        .arg(i + 1)
        .arg(q(l.name))
        .arg(q(formatNumber(l.recording.wavelength_nm)));
  }
  if (int i = indexedElement(id, "stages"); i >= 0 && i < static_cast<int>(scene.stages.size())) {
    const auto& s = scene.stages[static_cast<std::size_t>(i)];
    return QStringLiteral("Stage %1: %2 %3 (%4 %5)")
        .arg(i + 1)
        .arg(q(s.element), q(s.axis), q(s.controller), q(s.stage_model));
  }
  return id;
}

bool messageConcerns(const QString& message, const QString& id) {
  return message.startsWith(id + ".") || message.startsWith(id + ":") || message.startsWith(id + "[");
}

}  // namespace fovea::viz
