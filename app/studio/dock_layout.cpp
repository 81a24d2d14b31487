#include "app/studio/dock_layout.h"

#include <QDockWidget>
#include <QMainWindow>
#include <QScrollArea>
#include <QScrollBar>

#include <algorithm>
#include <vector>

namespace fovea::studio {

namespace {

// The default tab groups: the first dock of each group is in front.
struct DockGroup {
  Qt::DockWidgetArea area;
  std::vector<const char*> docks;
};

const std::vector<DockGroup>& defaultGroups() {
  static const std::vector<DockGroup> groups = {
      {Qt::LeftDockWidgetArea, {"SceneTreeDock"}},
      {Qt::LeftDockWidgetArea, {"GazeDock", "RaysDock"}},
      {Qt::RightDockWidgetArea, {"PropertiesDock", "AnalysesDock", "DevicesDock", "TopViewDock"}},
      {Qt::RightDockWidgetArea, {"RetinaDock", "KSpaceDock", "PreviewDock"}},
      {Qt::BottomDockWidgetArea, {"MessagesDock", "PlotsDock"}},
  };
  return groups;
}

}  // namespace

QWidget* scrollableDockContent(QWidget* panel) {
  // One scroll area per dock: a panel that scrolls its own form (the properties, the
  // analyses) keeps its buttons in view and is not put in a second, outer one.
  if (qobject_cast<QAbstractScrollArea*>(panel) || panel->findChild<QScrollArea*>()) return panel;
  auto* scroll = new QScrollArea;
  scroll->setObjectName(panel->objectName().isEmpty() ? QString("dockScroll") : panel->objectName() + "Scroll");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  // Tab goes to the fields inside, not to the frameless (so invisible) scroll area itself.
  scroll->setFocusPolicy(Qt::NoFocus);
  scroll->setWidget(panel);
  return scroll;
}

void applyDefaultDockLayout(QMainWindow* window) {
  // Bottom docks span only the centre: the side columns keep the full height.
  window->setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
  window->setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
  // Take every known dock out first: tabifyDockWidget() and splitDockWidget() never undo
  // an earlier tab group, so re-adding is the only way to rebuild the groups.
  for (const DockGroup& group : defaultGroups())
    for (const char* name : group.docks)
      if (auto* dock = window->findChild<QDockWidget*>(name)) {
        dock->setFloating(false);  // a floating dock is not in the layout to be removed from
        window->removeDockWidget(dock);
      }
  // First the front dock of every group, stacked per area; then the other docks as tabs
  // behind their front (splitDockWidget() on a tabbed dock would add a tab, not a split).
  auto areaIndex = [](Qt::DockWidgetArea a) {
    return a == Qt::LeftDockWidgetArea ? 0 : a == Qt::RightDockWidgetArea ? 1 : 2;
  };
  QDockWidget* lastInArea[3] = {nullptr, nullptr, nullptr};
  std::vector<QDockWidget*> fronts(defaultGroups().size(), nullptr);
  for (std::size_t g = 0; g < defaultGroups().size(); ++g) {
    const DockGroup& group = defaultGroups()[g];
    for (const char* name : group.docks) {
      auto* dock = window->findChild<QDockWidget*>(name);
      if (!dock) continue;
      dock->setFloating(false);
      const Qt::Orientation along = group.area == Qt::BottomDockWidgetArea ? Qt::Horizontal : Qt::Vertical;
      window->addDockWidget(group.area, dock, along);
      QDockWidget*& above = lastInArea[areaIndex(group.area)];
      if (above) window->splitDockWidget(above, dock, Qt::Vertical);
      above = dock;
      fronts[g] = dock;
      dock->show();
      break;
    }
  }
  for (std::size_t g = 0; g < defaultGroups().size(); ++g) {
    if (!fronts[g]) continue;
    for (const char* name : defaultGroups()[g].docks) {
      auto* dock = window->findChild<QDockWidget*>(name);
      if (!dock || dock == fronts[g]) continue;
      dock->setFloating(false);
      window->tabifyDockWidget(fronts[g], dock);
      dock->show();
    }
    fronts[g]->raise();
  }
  // Proportions: side columns about a fifth and a quarter of the width, the bottom strip
  // a sixth of the height; the upper group of each column gets a little more than half.
  const int w = std::max(window->width(), 800), h = std::max(window->height(), 600);
  auto dock = [window](const char* name) { return window->findChild<QDockWidget*>(name); };
  if (auto* tree = dock("SceneTreeDock"), *props = dock("PropertiesDock"); tree && props)
    window->resizeDocks({tree, props}, {std::clamp(w / 5, 220, 340), std::clamp(w / 4, 300, 440)}, Qt::Horizontal);
  if (auto* messages = dock("MessagesDock"))
    window->resizeDocks({messages}, {std::clamp(h / 6, 110, 220)}, Qt::Vertical);
  const int column = h - 90;  // menu bar, status bar, dock titles
  if (auto* tree = dock("SceneTreeDock"), *gaze = dock("GazeDock"); tree && gaze)
    window->resizeDocks({tree, gaze}, {column * 45 / 100, column * 55 / 100}, Qt::Vertical);
  if (auto* props = dock("PropertiesDock"), *retina = dock("RetinaDock"); props && retina)
    window->resizeDocks({props, retina}, {column * 55 / 100, column * 45 / 100}, Qt::Vertical);
}

void widenDockToFit(QMainWindow* window, QDockWidget* dock) {
  // Only a dock the user sees: not one tabbed behind another or in a window not yet shown.
  if (!window || !dock || dock->isFloating() || !dock->isVisible() || dock->visibleRegion().isEmpty()) return;
  QWidget* content = dock->widget();
  if (!content) return;
  int wanted = content->sizeHint().width();
  if (auto* scroll = qobject_cast<QScrollArea*>(content); scroll && scroll->widget())
    wanted = scroll->widget()->sizeHint().width() + scroll->verticalScrollBar()->sizeHint().width() +
             2 * scroll->frameWidth();
  // The dock's own frame and margins around its widget.
  wanted += dock->width() - content->width();
  // At most what leaves the central widget (the 3-D view) 30 % of the window.
  const int spare = window->centralWidget() ? window->centralWidget()->width() - window->width() * 3 / 10 : 0;
  const int target = std::min(wanted, dock->width() + std::max(0, spare));
  if (target > dock->width()) window->resizeDocks({dock}, {target}, Qt::Horizontal);
}

}  // namespace fovea::studio
