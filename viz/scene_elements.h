#pragma once
// Names of the scene's elements shared by the 3D view, the scene tree and the property
// editor. An element id is the element's path in the scene file, as the loader's messages
// spell it: "projector", "hoe", "hoe_layers[1]", "eye", "foveal_display",
// "beam_shaping_lens", "foveation", "stages[0]", and "binocular" for a binocular scene.

#include <QString>
#include <QStringList>

#include "model/scene/scene.h"

namespace fovea::viz {

QString hoeLayerId(int index);
QString stageId(int index);
// Index in "hoe_layers[i]" / "stages[i]" for the given prefix, or -1.
int indexedElement(const QString& id, const QString& prefix);

// Every element of the scene, in tree order.
QStringList elementIds(const Scene& scene);
// A human title: "Projector — laser scanning projector", "HOE layer 2 (green, 532 nm)".
QString elementTitle(const Scene& scene, const QString& id);
// True when `message` (a validateScene() message "path: problem") concerns element `id`.
bool messageConcerns(const QString& message, const QString& id);

}  // namespace fovea::viz
