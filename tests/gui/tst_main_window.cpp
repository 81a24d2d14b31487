// The studio's main window under Xvfb: default scene, undoable property edits with inline
// refusals, selection synced between the tree and the 3D view, a bad file that keeps the
// current scene, QSaveFile saves, and a screenshot that shows the scene's actors.
#include <QtTest>

#include <QAbstractButton>
#include <QDockWidget>
#include <QLineEdit>
#include <QMessageBox>
#include <QTreeWidgetItem>
#include <QUndoStack>

#include <vtkProp.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <vtkVersion.h>
#include <opencv2/core/version.hpp>

#include "app/studio/about_text.h"
#include "app/studio/main_window.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"
#include "viz/scene_actors.h"
#include "viz/scene_view.h"
#include "viz/vtk_gl_widget.h"
#include "widgets/message_log.h"
#include "widgets/preferences.h"
#include "widgets/property_editor.h"
#include "widgets/scene_document.h"
#include "widgets/scene_tree.h"

namespace tst_main_window {

using namespace fovea;

namespace {

std::filesystem::path tmpDir() {
  auto d = std::filesystem::path(qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp").toStdString()) / "gui_main_window";
  std::filesystem::create_directories(d);
  return d;
}

std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Pixels of `image` inside `rect` that `pred(r, g, b)` accepts.
template <class Pred>
int countPixels(const QImage& image, const QRect& rect, Pred pred) {
  int n = 0;
  for (int y = rect.top(); y <= rect.bottom(); ++y)
    for (int x = rect.left(); x <= rect.right(); ++x) {
      const QRgb c = image.pixel(x, y);
      if (pred(qRed(c), qGreen(c), qBlue(c))) ++n;
    }
  return n;
}

double lumaVariance(const QImage& image, const QRect& rect) {
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = rect.top(); y <= rect.bottom(); y += 2)
    for (int x = rect.left(); x <= rect.right(); x += 2) {
      const double v = qGray(image.pixel(x, y));
      sum += v;
      sum2 += v * v;
      ++n;
    }
  const double mean = sum / n;
  return sum2 / n - mean * mean;
}

// Near the micro-OLED's cyan, and bright near-white like the lit eyeball (the background
// gradient is dark blue-grey, at most ~85 in any channel).
bool cyanish(int r, int g, int b) {
  return g > 120 && b > 120 && r < 90 && std::abs(g - b) < 60;
}
// The muted, half-transparent eyeball over the dark background: a warm mid grey. (The
// scale bar's and labels' neutral white and grey, r == b, are excluded.)
bool eyeballish(int r, int g, int b) {
  return r > 90 && r < 200 && r - b >= 3 && r - b < 25 && std::abs(r - g) < 10;
}

// Answers the next modal message box with `button`, recording its text in `asked`.
void answerNextMessageBox(QMessageBox::StandardButton button, QString* asked) {
  auto* timer = new QTimer;
  timer->setInterval(20);
  QObject::connect(timer, &QTimer::timeout, [timer, button, asked] {
    auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
    if (!box) return;
    *asked = box->text();
    timer->stop();
    timer->deleteLater();
    box->button(button)->click();
  });
  timer->start();
}

}  // namespace

class TestMainWindow : public QObject {
  Q_OBJECT
 private:
  std::unique_ptr<studio::MainWindow> w;

 private slots:
  void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

  void init() {
    w = std::make_unique<studio::MainWindow>();
    w->resize(1400, 900);
    w->show();
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    w->sceneView()->renderToImage();  // GL initialised, renderer sized
  }
  void cleanup() {
    // Discard edits so closing asks nothing.
    w->document()->undoStack()->setClean();
    w.reset();
  }

  void opensTheDefaultScene() {
    const Scene& s = w->document()->scene();
    QCOMPARE(s.name, std::string("Optical bench prototype"));
    QCOMPARE(s.eye.relief_mm, 22.0);
    QCOMPARE(s.hoe_layers.size(), std::size_t{3});
    QVERIFY(w->windowTitle().startsWith("prototype-bench.json (embedded)[*]"));
    QVERIFY(!w->isWindowModified());
    QVERIFY(w->sceneTree()->itemFor("hoe_layers[2]"));
    QVERIFY(w->sceneTree()->itemFor("stages[4]"));
    // Every drawn element has actors; the view shows the document's scene.
    for (const char* id : {"projector", "hoe", "hoe_layers[0]", "hoe_layers[1]", "hoe_layers[2]", "eye",
                           "foveal_display", "beam_shaping_lens"})
      QVERIFY2(!w->sceneView()->sceneLayer().propsOf(id).empty(), id);
    QVERIFY(w->sceneView()->scene() == s);
    // Real sizes: the 44 x 36 mm HOE, the HOE's x stage travelling -8..+8 mm (end stops of
    // 0.8 mm radius); the gaze camera's rotation stage is not drawn.
    auto bounds = [&](const char* id, const char* layer = "scene") {
      std::array<double, 6> b{1e9, -1e9, 1e9, -1e9, 1e9, -1e9};
      for (vtkProp* p : w->sceneView()->layer(layer).propsOf(id)) {
        const double* pb = p->GetBounds();
        for (int i = 0; i < 3; ++i) {
          b[2 * i] = std::min(b[2 * i], pb[2 * i]);
          b[2 * i + 1] = std::max(b[2 * i + 1], pb[2 * i + 1]);
        }
      }
      return b;
    };
    const auto hoe = bounds("hoe_layers[1]");
    QCOMPARE(hoe[0], -22.0);
    QCOMPARE(hoe[1], 22.0);
    QCOMPARE(hoe[2], -18.0);
    QCOMPARE(hoe[3], 18.0);
    const auto stage = bounds("stages[0]", "stages");                             // the stages have their own layer
    QVERIFY2(std::abs(stage[0] + 8.8) < 1e-3 && std::abs(stage[1] - 8.8) < 1e-3,  // tessellated stops
             qPrintable(QString("stage x from %1 to %2").arg(stage[0]).arg(stage[1])));
    QVERIFY(w->sceneView()->layer("stages").propsOf("stages[4]").empty());
    QVERIFY(w->sceneView()->sceneLayer().propsOf("stages[0]").empty());
    // Once, beside the bench's own start-up messages (they reach the Messages dock too).
    const QStringList opened = w->messageLog()->entries().filter("Opened the default scene");
    QVERIFY2(opened.size() == 1 && opened.first().startsWith("info: Opened the default scene: Optical bench prototype"),
             qPrintable(w->messageLog()->entries().join(" | ")));
  }

  void propertyEditIsUndoable() {
    w->selectElement("eye");
    auto* editor = w->propertyEditor();
    QUndoStack* stack = w->document()->undoStack();
    QSignalSpy stackSpy(stack, &QUndoStack::indexChanged);
    QSignalSpy sceneSpy(w->document(), &widgets::SceneDocument::sceneChanged);
    auto* field = qobject_cast<QLineEdit*>(editor->fieldFor("eye.relief_mm"));
    QVERIFY(field);
    QCOMPARE(field->text(), QString("22"));

    // Typed into the field and confirmed with Enter, as a user does.
    field->setFocus();
    field->selectAll();
    QTest::keyClicks(field, "25.5");
    QTest::keyClick(field, Qt::Key_Return);
    QCOMPARE(w->document()->scene().eye.relief_mm, 25.5);
    QCOMPARE(stackSpy.count(), 1);
    QCOMPARE(sceneSpy.count(), 1);
    QCOMPARE(stack->undoText(), QString("Set eye relief to 25.5 mm"));
    QVERIFY(w->isWindowModified());
    // The 3D view follows the model: the eye moved 3.5 mm back with the relief.
    QCOMPARE(placeEye(w->sceneView()->scene()).rotation_center.z(), -(25.5 + 11.5));

    stack->undo();
    QCOMPARE(w->document()->scene().eye.relief_mm, 22.0);
    QCOMPARE(field->text(), QString("22"));
    QVERIFY(!w->isWindowModified());
    QCOMPARE(placeEye(w->sceneView()->scene()).rotation_center.z(), -(22.0 + 11.5));
    stack->redo();
    QCOMPARE(w->document()->scene().eye.relief_mm, 25.5);
    QCOMPARE(field->text(), QString("25.5"));
    QCOMPARE(stackSpy.count(), 3);
    QCOMPARE(sceneSpy.count(), 3);
  }

  void propertyEditorFollowsTheDisplayUnits() {
    widgets::Preferences& prefs = widgets::Preferences::instance();
    const widgets::PreferenceValues saved = prefs.values();
    w->selectElement("eye");
    auto* editor = w->propertyEditor();
    QUndoStack* stack = w->document()->undoStack();
    auto* relief = qobject_cast<QLineEdit*>(editor->fieldFor("eye.relief_mm"));
    QVERIFY(relief);
    QCOMPARE(editor->unitFor("eye.relief_mm"), QString("mm"));

    // Switching the preference updates the open editor: inches and radians.
    widgets::PreferenceValues v = saved;
    v.length = widgets::LengthUnit::Inch;
    v.angle = widgets::AngleUnit::Radian;
    prefs.setValues(v);
    relief = qobject_cast<QLineEdit*>(editor->fieldFor("eye.relief_mm"));
    QVERIFY(relief);
    QCOMPARE(editor->unitFor("eye.relief_mm"), QString("in"));
    QCOMPARE(editor->unitFor("eye.gaze_deg[0]"), QString("rad"));
    QCOMPARE(editor->unitFor("eye.pupil_diameter_mm"), QString("in"));
    QCOMPARE(relief->text().toDouble(), 22.0 / 25.4);
    // The range shown is converted too: pupil diameter (0, 15) mm.
    auto* pupil = qobject_cast<QLineEdit*>(editor->fieldFor("eye.pupil_diameter_mm"));
    QCOMPARE(pupil->placeholderText(), QString("(0, %1)").arg(15.0 / 25.4, 0, 'g', 6));
    // For a look: the editor in inches and radians.
    QTest::qWait(50);  // lay the rebuilt form out
    editor->grab().save(qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/property-editor-in-rad.png");

    // Typed in inches: the model gets millimetres, one undo step named in the shown unit.
    relief->setFocus();
    relief->selectAll();
    QTest::keyClicks(relief, "1");
    QTest::keyClick(relief, Qt::Key_Return);
    QCOMPARE(w->document()->scene().eye.relief_mm, 25.4);
    QCOMPARE(stack->count(), 1);
    QCOMPARE(stack->undoText(), QString("Set eye relief to 1 in"));
    // Radians: a gaze of 0.1 rad.
    QCOMPARE(editor->commitText("eye.gaze_deg[0]", "0.1"), QString());
    QCOMPARE(w->document()->scene().eye.gaze_deg[0], 0.1 * 180.0 / M_PI);
    QCOMPARE(stack->count(), 2);
    // A refused value (checked by the model in mm) leaves the model unchanged.
    QVERIFY(!editor->commitText("eye.relief_mm", "-1").isEmpty());
    QCOMPARE(w->document()->scene().eye.relief_mm, 25.4);
    QCOMPARE(stack->count(), 2);

    // Micrometres: the field shows the same relief in µm.
    v.length = widgets::LengthUnit::Micrometre;
    prefs.setValues(v);
    QCOMPARE(editor->unitFor("eye.relief_mm"), QString("µm"));
    QCOMPARE(qobject_cast<QLineEdit*>(editor->fieldFor("eye.relief_mm"))->text().toDouble(), 25400.0);
    QCOMPARE(editor->commitText("eye.relief_mm", "23500"), QString());
    QCOMPARE(w->document()->scene().eye.relief_mm, 23.5);
    stack->undo();
    QCOMPARE(w->document()->scene().eye.relief_mm, 25.4);
    prefs.setValues(saved);
    QCOMPARE(editor->unitFor("eye.relief_mm"), QString("mm"));
    QCOMPARE(qobject_cast<QLineEdit*>(editor->fieldFor("eye.relief_mm"))->text(), QString("25.4"));
  }

  void badValueIsRefusedWithTheRule() {
    w->selectElement("hoe_layers[1]");
    auto* editor = w->propertyEditor();
    const Scene before = w->document()->scene();
    QSignalSpy refused(editor, &widgets::PropertyEditor::editRefused);
    // Units as printed, and the table's help text in the tooltip.
    QCOMPARE(editor->unitFor("hoe_layers[1].thickness_um"), QString("µm"));
    QVERIFY(editor->fieldFor("hoe_layers[1].thickness_um")->toolTip().startsWith("film thickness\n"));
    // The messages name the field by its label, as the editor shows it.
    QCOMPARE(editor->commitText("hoe_layers[1].thickness_um", "-5"), QString("Thickness: must be > 0, got -5"));
    QCOMPARE(editor->messageFor("hoe_layers[1].thickness_um"), QString("Thickness: must be > 0, got -5"));
    QCOMPARE(editor->commitText("hoe_layers[1].n1", "1.7"),
             QString("Index modulation n1: must be < n0 (1.5), got 1.7"));
    QCOMPARE(editor->commitText("hoe_layers[1].n0", "abc"), QString("Mean index n0: not a number: \"abc\""));
    QCOMPARE(refused.count(), 3);
    QVERIFY(w->document()->scene() == before);
    QCOMPARE(w->document()->undoStack()->count(), 0);
    QVERIFY(w->messageLog()->entries().last().startsWith("warning: edit refused: Mean index n0: not a number"));
    // A good value afterwards clears the message and is applied.
    QCOMPARE(editor->commitText("hoe_layers[1].thickness_um", "20"), QString());
    QCOMPARE(w->document()->scene().hoe_layers[1].thickness_um, 20.0);
    QCOMPARE(editor->messageFor("hoe_layers[1].thickness_um"), QString());
  }

  void treeSelectionSelectsInView() {
    QTreeWidgetItem* item = w->sceneTree()->itemFor("foveal_display");
    QVERIFY(item);
    w->sceneTree()->setCurrentItem(item);  // what a click in the tree does
    QCOMPARE(w->selectedElement(), QString("foveal_display"));
    QCOMPARE(w->sceneView()->selectedElement(), QString("foveal_display"));
    QCOMPARE(w->propertyEditor()->element(), QString("foveal_display"));
    QVERIFY(w->propertyEditor()->fieldFor("foveal_display.combiner.magnification"));
  }

  void clickInViewSelectsInTree() {
    viz::SceneView* view = w->sceneView();
    view->showStandardView(viz::StandardView::Side);
    view->renderToImage();
    // Click on the eyeball's centre as seen from the side.
    const auto eye = view->widgetPositionOf(placeEye(w->document()->scene()).rotation_center);
    QVERIFY(eye.has_value());
    QVERIFY(view->rect().contains(eye->toPoint()));
    QCOMPARE(view->elementAt(*eye), QString("eye"));
    QTest::mouseClick(view, Qt::LeftButton, {}, eye->toPoint());
    QCOMPARE(w->sceneTree()->selectedElement(), QString("eye"));
    QCOMPARE(w->propertyEditor()->element(), QString("eye"));
    // The micro-OLED seen from above, clicked on its back away from its stage bars (which
    // run through its centre along local x and y).
    view->showStandardView(viz::StandardView::Top);
    view->renderToImage();
    const Frame panel = frameOf(w->document()->scene().foveal_display.pose);
    const auto oled = view->widgetPositionOf(panel.toBench({3.9, 2.2, -1.0}));
    QVERIFY(oled.has_value());
    // Nothing selected, so no handle of the eye (its rings reach over the panel from the
    // top) takes the click.
    w->selectElement({});
    QTest::mouseClick(view, Qt::LeftButton, {}, oled->toPoint());
    QCOMPARE(w->sceneTree()->selectedElement(), QString("foveal_display"));
    // Empty background clears the selection.
    QTest::mouseClick(view, Qt::LeftButton, {}, QPoint(5, 5));
    QCOMPARE(w->sceneTree()->selectedElement(), QString());
    QCOMPARE(view->selectedElement(), QString());
  }

  void badFileKeepsTheCurrentScene() {
    w->selectElement("eye");
    QCOMPARE(w->propertyEditor()->commitText("eye.relief_mm", "24"), QString());
    const Scene before = w->document()->scene();
    std::string text = serializeScene(before);
    text.replace(text.find("\"relief_mm\": 24.0"), 17, "\"relief_mm\": -5");
    text.replace(text.find("\"pupil_diameter_mm\": 5.0"), 24, "\"pupil_diameter_mm\": \"5\"");
    const auto path = tmpDir() / "bad.json";
    std::ofstream(path) << text;
    QVERIFY(!w->openFile(QString::fromStdString(path.string()), false));
    QVERIFY(w->document()->scene() == before);
    QVERIFY(w->document()->isModified());
    QVERIFY(w->document()->filePath().isEmpty());
    const QStringList log = w->messageLog()->entries();
    QVERIFY(log.contains("error: bad.json: eye.pupil_diameter_mm: must be a number, got a string"));
    QVERIFY(log.contains("error: bad.json: eye.relief_mm: must be > 0, got -5"));
  }

  void saveAndReopen() {
    w->selectElement("eye");
    QCOMPARE(w->propertyEditor()->commitText("eye.gaze_deg[0]", "10"), QString());
    const auto path = tmpDir() / "saved.json";
    std::filesystem::remove(path);
    QVERIFY(w->saveTo(QString::fromStdString(path.string()), false));
    QVERIFY(!w->isWindowModified());
    QVERIFY(w->windowTitle().startsWith("saved.json[*]"));
    QCOMPARE(readText(path), serializeScene(w->document()->scene()));
    QCOMPARE(w->recentFiles().first(), QString::fromStdString(path.string()));
    // A save into a missing folder fails and says so; the saved file is untouched.
    QVERIFY(!w->saveTo(QString::fromStdString((tmpDir() / "no-such-dir" / "x.json").string()), false));
    QVERIFY(w->messageLog()->entries().last().startsWith("error: Saving "));
    const Scene saved = w->document()->scene();
    w->openEmbeddedDefault();
    QCOMPARE(w->document()->scene().eye.gaze_deg[0], 0.0);
    QVERIFY(w->openFile(QString::fromStdString(path.string()), false));
    QVERIFY(w->document()->scene() == saved);
    QCOMPARE(w->document()->scene().eye.gaze_deg[0], 10.0);
  }

  void quittingWithUnsavedChangesAsks() {
    w->selectElement("eye");
    QCOMPARE(w->propertyEditor()->commitText("eye.relief_mm", "30"), QString());
    QVERIFY(w->isWindowModified());
    QVERIFY(w->windowTitle().startsWith("prototype-bench.json (embedded)[*]"));
    QString asked;
    answerNextMessageBox(QMessageBox::Cancel, &asked);
    QVERIFY(!w->close());
    QCOMPARE(asked, QString("prototype-bench.json (embedded) has unsaved changes. Save them?"));
    QVERIFY(w->isVisible());
    QCOMPARE(w->document()->scene().eye.relief_mm, 30.0);
    asked.clear();
    answerNextMessageBox(QMessageBox::Discard, &asked);
    QVERIFY(w->close());
    QVERIFY(!asked.isEmpty());
  }

  void settingsPersist() {
    // QSettings live under the test's scratch XDG_CONFIG_HOME (see main()).
    w->setPersistentSettings(true);
    const auto path = tmpDir() / "recent.json";
    QVERIFY(w->saveTo(QString::fromStdString(path.string()), false));
    w->findChild<QDockWidget*>("MessagesDock")->hide();
    QVERIFY(w->close());  // nothing unsaved: no question, settings written
    studio::MainWindow again;
    again.setPersistentSettings(true);
    again.restoreSettings();
    QCOMPARE(again.recentFiles().value(0), QString::fromStdString(path.string()));
    again.show();
    QVERIFY(QTest::qWaitForWindowExposed(&again));
    QVERIFY(!again.findChild<QDockWidget*>("MessagesDock")->isVisible());
    QVERIFY(again.findChild<QDockWidget*>("PropertiesDock")->isVisible());
  }

  void aboutNamesTheLibraryVersions() {
    const QString html = studio::versionsHtml();
    QVERIFY(html.contains(QString("<td>Qt</td><td>%1 ").arg(qVersion())));
    QVERIFY(html.contains(QString("<td>VTK</td><td>%1</td>").arg(vtkVersion::GetVTKVersion())));
    QVERIFY(html.contains(QString("<td>OpenCV</td><td>%1</td>").arg(CV_VERSION)));
  }

  void screenshotShowsTheScene() {
    viz::SceneView* view = w->sceneView();
    view->showStandardView(viz::StandardView::Isometric);
    const QImage shot = w->captureWindow();
    QCOMPARE(shot.size(), w->size());
    const QRect viewRect(view->mapTo(w.get(), QPoint(0, 0)), view->size());
    QVERIFY2(lumaVariance(shot, viewRect) > 100.0, "the 3D view is blank");
    // The scene's part of the view: above the scale bar and the axes marker (their
    // anti-aliased text has coloured fringes).
    const QRect sceneRect = viewRect.adjusted(0, 0, 0, -viewRect.height() / 4);
    const int cyan = countPixels(shot, sceneRect, cyanish), white = countPixels(shot, sceneRect, eyeballish);
    QVERIFY2(cyan > 100, qPrintable(QString("micro-OLED pixels: %1").arg(cyan)));
    QVERIFY2(white > 300, qPrintable(QString("eyeball pixels: %1").arg(white)));
    // Those pixels are the actors': with the scene layer hidden they are gone.
    view->sceneLayer().setVisible(false);
    view->layer("frustum").setVisible(false);
    view->setLabelsVisible(false);
    const QImage empty = w->captureWindow();
    QCOMPARE(countPixels(empty, sceneRect, cyanish), 0);
    QCOMPARE(countPixels(empty, sceneRect, eyeballish), 0);
    view->sceneLayer().setVisible(true);
    view->layer("frustum").setVisible(true);
    view->setLabelsVisible(true);
  }
};

int main(int argc, char** argv) {
  viz::installDefaultSurfaceFormat();  // before the QApplication, as fovea-studio does
  const auto config = tmpDir() / "config";
  std::filesystem::remove_all(config);
  qputenv("XDG_CONFIG_HOME", QByteArray::fromStdString(config.string()));
  QApplication app(argc, argv);
  QApplication::setOrganizationName("FoveatedARStudioTest");
  QApplication::setApplicationName("tst_main_window");
  TestMainWindow test;
  return QTest::qExec(&test, argc, argv);
}

}  // namespace tst_main_window
#include "tst_main_window.moc"
