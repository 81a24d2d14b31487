// The 3-D view of a binocular scene (issue 30): the left eye's mirrored train in its own layer
// ("left-train") beside the scene's (right) train, nothing of it for a monocular scene; a gaze
// change redraws its eye without duplicating it; the HOE display shift is mirrored.
#include <QtTest>
#include "tests/test_paths.h"

#include <cmath>
#include <string>

#include <vtkProp.h>
#include <vtkProp3D.h>

#include "model/scene/eye_scene.h"
#include "model/scene/scene_io.h"
#include "viz/scene_elements.h"
#include "viz/scene_view.h"

namespace tst_binocular_view {

using namespace fovea;

namespace {
Scene loadOrFail(const char* rel) {
  SceneLoadResult r = loadSceneFile(std::string(FOVEA_SOURCE_DIR) + "/" + rel);
  if (!r.ok()) qFatal("%s: %s", rel, r.errors.front().c_str());
  return *r.scene;
}
// Centre x of the union of the props' bounds (mm).
double centreX(const std::vector<vtkProp*>& props) {
  double lo = 1e300, hi = -1e300;
  for (vtkProp* p : props)
    if (const double* b = p->GetBounds()) lo = std::min(lo, b[0]), hi = std::max(hi, b[1]);
  return (lo + hi) / 2;
}
}  // namespace

class TestBinocularView : public QObject {
  Q_OBJECT
 private slots:
  void drawsBothTrains() {
    viz::SceneView view;
    view.resize(800, 600);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setScene(loadOrFail("resources/scenes/prototype-bench.json"), true);
    QCOMPARE(view.layer("left-train").size(), std::size_t{0});

    const Scene bino = loadOrFail("resources/scenes/binocular-prototype.json");
    view.setScene(bino, true);
    viz::SceneLayer& left = view.layer("left-train");
    const std::size_t props = left.size();
    QVERIFY(props > 0);
    // The left HOE is the right one mirrored about x = -31.5: centred at -63 instead of 0.
    const double right_hoe = centreX(view.sceneLayer().propsOf("hoe"));
    const double left_hoe = centreX(left.propsOf("hoe"));
    QVERIFY2(std::abs(right_hoe - 0.0) < 1e-6, qPrintable(QString::number(right_hoe)));
    QVERIFY2(std::abs(left_hoe + 63.0) < 1e-6, qPrintable(QString::number(left_hoe)));
    const double right_projector = centreX(view.sceneLayer().propsOf("projector"));
    const double left_projector = centreX(left.propsOf("projector"));
    QVERIFY2(std::abs((left_projector + 31.5) + (right_projector + 31.5)) < 1e-6,
             qPrintable(QString("%1 %2").arg(left_projector).arg(right_projector)));
    QVERIFY(!left.propsOf("eye").empty());
    QVERIFY(!left.propsOf("foveal_display").empty());
    // The scene tree and property editor get the block as an element.
    QVERIFY(viz::elementIds(bino).contains("binocular"));
    QVERIFY(!viz::elementIds(loadOrFail("resources/scenes/prototype-bench.json")).contains("binocular"));
    QCOMPARE(viz::elementTitle(bino, "binocular"), QString("Binocular — mirror, IPD 63 mm"));

    // A gaze change takes the cheap path and redraws the left eye once.
    Scene turned = bino;
    turned.eye.gaze_deg = {12.0, 0.0};
    view.setScene(turned);
    QCOMPARE(left.size(), props);
    // The HOE display shift: mirrored for the left train.
    view.setHoeDisplayShift({2.0, 0.5, 0.0});
    auto* p3 = vtkProp3D::SafeDownCast(left.propsOf("hoe").front());
    QVERIFY(p3);
    QCOMPARE(p3->GetPosition()[0], -2.0);
    QCOMPARE(p3->GetPosition()[1], 0.5);
    auto* r3 = vtkProp3D::SafeDownCast(view.sceneLayer().propsOf("hoe").front());
    QCOMPARE(r3->GetPosition()[0], 2.0);
    // Back to a monocular scene: the left train goes.
    view.setScene(loadOrFail("resources/scenes/prototype-bench.json"));
    QCOMPARE(left.size(), std::size_t{0});
    // The eye's view hides it.
    view.setScene(bino);
    view.showStandardView(viz::StandardView::EyeView);
    QVERIFY(!left.isVisible());
    view.showStandardView(viz::StandardView::Top);
    QVERIFY(left.isVisible());
  }
};

QTEST_MAIN(TestBinocularView)

}  // namespace tst_binocular_view
#include "tst_binocular_view.moc"
