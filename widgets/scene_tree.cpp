#include "widgets/scene_tree.h"

#include <QHeaderView>

#include "viz/scene_elements.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

namespace {
constexpr int kIdRole = Qt::UserRole + 1;
}

SceneTree::SceneTree(SceneDocument* document, QWidget* parent) : QTreeWidget(parent), document_(document) {
  setHeaderHidden(true);
  setColumnCount(1);
  setSelectionMode(QAbstractItemView::SingleSelection);
  setUniformRowHeights(true);
  connect(document_, &SceneDocument::sceneChanged, this, [this] {
    if (viz::elementIds(document_->scene()) != ids_)
      rebuild();
    else
      updateTitles();
  });
  connect(this, &QTreeWidget::itemSelectionChanged, this, [this] { emit elementSelected(selectedElement()); });
  rebuild();
}

void SceneTree::rebuild() {
  const QString keep = selectedElement();
  QSignalBlocker block(this);
  clear();
  const Scene& scene = document_->scene();
  ids_ = viz::elementIds(scene);
  QTreeWidgetItem* hoe = nullptr;
  QTreeWidgetItem* stages = nullptr;
  for (const QString& id : ids_) {
    QTreeWidgetItem* parentItem = nullptr;
    if (id.startsWith("hoe_layers[")) parentItem = hoe;
    if (id.startsWith("stages[")) {
      if (!stages) {
        stages = new QTreeWidgetItem(this, {tr("Stage axes")});
        stages->setFlags(Qt::ItemIsEnabled);
      }
      parentItem = stages;
    }
    auto* item = parentItem ? new QTreeWidgetItem(parentItem) : new QTreeWidgetItem(this);
    item->setData(0, kIdRole, id);
    if (id == "hoe") hoe = item;
  }
  updateTitles();
  expandAll();
  if (QTreeWidgetItem* item = itemFor(keep)) item->setSelected(true);
}

void SceneTree::updateTitles() {
  const Scene& scene = document_->scene();
  for (QTreeWidgetItemIterator it(this); *it; ++it) {
    const QString id = (*it)->data(0, kIdRole).toString();
    if (id.isEmpty()) continue;
    (*it)->setText(0, viz::elementTitle(scene, id));
    (*it)->setToolTip(0, id);
  }
}

QTreeWidgetItem* SceneTree::itemFor(const QString& id) const {
  if (id.isEmpty()) return nullptr;
  for (QTreeWidgetItemIterator it(const_cast<SceneTree*>(this)); *it; ++it)
    if ((*it)->data(0, kIdRole).toString() == id) return *it;
  return nullptr;
}

QString SceneTree::selectedElement() const {
  const auto items = selectedItems();
  return items.isEmpty() ? QString() : items.front()->data(0, kIdRole).toString();
}

void SceneTree::setSelectedElement(const QString& id) {
  QSignalBlocker block(this);
  clearSelection();
  if (QTreeWidgetItem* item = itemFor(id)) {
    item->setSelected(true);
    setCurrentItem(item);
    scrollToItem(item);
  }
}

}  // namespace fovea::widgets
