#pragma once
// The scene tree: every element of the open scene (HOE layers under the HOE, stage axes
// under "Stages"). Selecting an item emits elementSelected(id); setSelectedElement() follows
// a selection made elsewhere (the 3D view) without emitting.

#include <QTreeWidget>

namespace fovea::widgets {

class SceneDocument;

class SceneTree : public QTreeWidget {
  Q_OBJECT
 public:
  explicit SceneTree(SceneDocument* document, QWidget* parent = nullptr);

  void setSelectedElement(const QString& id);
  QString selectedElement() const;
  QTreeWidgetItem* itemFor(const QString& id) const;

 signals:
  void elementSelected(const QString& id);

 private:
  void rebuild();
  void updateTitles();
  SceneDocument* document_;
  QStringList ids_;
};

}  // namespace fovea::widgets
