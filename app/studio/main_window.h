#pragma once
// The studio's main window: the 3D scene view in the centre, docks around it (scene tree,
// properties, messages; later features add theirs with addPanel()), menus with shortcuts,
// an undo stack for every edit, QSettings for geometry, dock state and recent files.

#include <QMainWindow>
#include <QStringList>

class QAction;
class QMenu;
class QDockWidget;
class QLabel;

namespace fovea {
struct Scene;
namespace viz {
class SceneView;
}
namespace widgets {
class SceneDocument;
class SceneTree;
class PropertyEditor;
class MessageLog;
class PreviewPanel;
class DevicesPanel;
}  // namespace widgets
}  // namespace fovea

namespace fovea::studio {

class AnalysisFeatures;
class LiveTraceFeatures;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Opens the embedded prototype bench (no file; "Save" asks for a name).
  void openEmbeddedDefault();
  // Loads a scene file. On any problem the current scene stays, every problem goes to the
  // messages dock (and a dialog when `interactive`), and false is returned.
  bool openFile(const QString& path, bool interactive = true);
  // Saves through QSaveFile: a failed save leaves an existing file untouched.
  bool saveTo(const QString& path, bool interactive = true);

  // Adds a dockable panel with a toggle in the View menu; returns its dock.
  QDockWidget* addPanel(QWidget* panel, const QString& title, const QString& objectName, Qt::DockWidgetArea area);

  // Selects an element everywhere (tree, 3D view, property editor); empty clears.
  void selectElement(const QString& id);
  QString selectedElement() const { return selected_; }

  // The whole window as the user sees it, with the 3D view's OpenGL content composited.
  QImage captureWindow();

  // Off by default in tests and screenshots: whether QSettings are read and written.
  void setPersistentSettings(bool on) { persistSettings_ = on; }
  void restoreSettings();
  // View ▸ Reset Layout: the default dock arrangement (dock_layout.h) and camera.
  void resetLayout();

  widgets::SceneDocument* document() const { return document_; }
  viz::SceneView* sceneView() const { return view_; }
  widgets::SceneTree* sceneTree() const { return tree_; }
  widgets::PropertyEditor* propertyEditor() const { return properties_; }
  widgets::MessageLog* messageLog() const { return log_; }
  QAction* labelsAction() const { return labelsAction_; }
  // The live bench (devices/bench): the virtual one when no stage controller is plugged in.
  widgets::DevicesPanel* devicesPanel() const { return devices_; }
  QDockWidget* devicesDock() const { return devicesDock_; }
  // The Foveated preview dock and its panel (Displays / Retina image modes).
  widgets::PreviewPanel* previewPanel() const { return preview_; }
  QDockWidget* previewDock() const { return previewDock_; }
  // Whether new main windows start the bench by themselves (default true; GUI tests that do
  // not exercise the bench and the report mode turn it off).
  static void setBenchAutoStart(bool on);
  QStringList recentFiles() const { return recent_; }
  // Analyses, plots, preferences, report export, autosave and recovery (analysis_features.h).
  AnalysisFeatures* analysisFeatures() const { return analysisFeatures_; }
  // Live trace, ray fans, retina and grating-vector views, gaze, handles (live_trace_features.h).
  LiveTraceFeatures* liveTraceFeatures() const { return liveTraceFeatures_; }

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  void createDocks();
  void createMenus();
  void createBenchMenu();
  void newScene();
  void openDialog();
  bool save();
  bool saveAsDialog();
  void exportScreenshotDialog();
  void showAbout();
  bool maybeDiscardChanges();
  void updateTitle();
  void addRecent(const QString& path);
  void fillRecentMenu();
  void saveSettings();
  QSize initialWindowSize() const;

  widgets::SceneDocument* document_ = nullptr;
  viz::SceneView* view_ = nullptr;
  widgets::SceneTree* tree_ = nullptr;
  widgets::PropertyEditor* properties_ = nullptr;
  widgets::MessageLog* log_ = nullptr;
  widgets::DevicesPanel* devices_ = nullptr;
  QDockWidget* devicesDock_ = nullptr;
  widgets::PreviewPanel* preview_ = nullptr;
  QDockWidget* previewDock_ = nullptr;
  QLabel* benchStatus_ = nullptr;  // permanent status-bar text: VIRTUAL BENCH / bench hardware
  QMenu* viewMenu_ = nullptr;
  QMenu* panelsMenu_ = nullptr;
  QMenu* recentMenu_ = nullptr;
  QAction* labelsAction_ = nullptr;  // View ▸ Element Labels (QSettings "view/labels")
  QString selected_;
  QStringList recent_;
  bool persistSettings_ = false;
  AnalysisFeatures* analysisFeatures_ = nullptr;
  LiveTraceFeatures* liveTraceFeatures_ = nullptr;
};

}  // namespace fovea::studio
