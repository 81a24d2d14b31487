// The grating-vector cloud (model/physics/grating_cloud.h): at the recording geometry the
// probe's K equals the recorded K; with the plate shifted the two keep the same tangential
// part and differ along the film normal only (the cloud along z), and the efficiency falls
// as that dephasing grows.
#include <QtTest>

#include <cmath>

#include "app/embedded_scene.h"
#include "model/physics/grating_cloud.h"
#include "model/physics/trace.h"
#include "model/scene/scene_io.h"

namespace tst_grating_cloud {

using namespace fovea;

class TestGratingCloud : public QObject {
  Q_OBJECT
 private:
  static std::vector<GratingVectorSample> cloud(const Scene& s, std::array<double, 2> shift) {
    TraceOptions o;
    o.rays = 1500;
    o.hoe_shift_mm = shift;
    return gratingVectorCloud(s, diffractScene(s, o), shift);
  }

 private slots:
  void braggMatchedInPlace() {
    const auto c = cloud(embeddedDefaultScene(), {0, 0});
    QVERIFY(c.size() > 1000);
    for (const auto& s : c) {
      QVERIFY((s.k_probe - s.k_recorded).norm() < 1e-9 * s.k_recorded.norm());
      // Each sample sits on the layer of its own colour.
      QCOMPARE(embeddedDefaultScene().hoe_layers[static_cast<std::size_t>(s.layer)].recording.wavelength_nm,
               s.wavelength_nm);
    }
  }

  void shiftedPlateSpreadsAlongTheNormal() {
    const auto c = cloud(embeddedDefaultScene(), {3.4, 0.0});
    QVERIFY(c.size() > 1000);
    double max_dz = 0;
    for (const auto& s : c) {
      const Eigen::Vector3d d = s.k_probe - s.k_recorded;
      QVERIFY(std::hypot(d.x(), d.y()) < 1e-9 * s.k_recorded.norm());
      max_dz = std::max(max_dz, std::abs(d.z()));
    }
    QVERIFY(max_dz > 0.01);  // rad/um: real dephasing somewhere on the plate
    // Efficiency falls with dephasing: the most mismatched tenth is less efficient on
    // average than the best matched tenth.
    std::vector<GratingVectorSample> v = c;
    std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
      return std::abs(a.k_probe.z() - a.k_recorded.z()) < std::abs(b.k_probe.z() - b.k_recorded.z());
    });
    const std::size_t n = v.size() / 10;
    double lo = 0, hi = 0;
    for (std::size_t i = 0; i < n; ++i) {
      lo += v[i].efficiency;
      hi += v[v.size() - 1 - i].efficiency;
    }
    QVERIFY(hi < lo);
  }

  void sampleCap() {
    QVERIFY(gratingVectorCloud(embeddedDefaultScene(), diffractScene(embeddedDefaultScene(), {}), {0, 0}, 500).size() <=
            500);
  }
};

QTEST_GUILESS_MAIN(TestGratingCloud)

}  // namespace tst_grating_cloud
#include "tst_grating_cloud.moc"
