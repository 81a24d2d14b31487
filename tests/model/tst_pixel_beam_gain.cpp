// Can any pixel beam give the seed's 14 % beam-shaping gain (A.2.2)? The lens can only beat
// the unshaped spot on the HOE by converging the beam harder than it already converges; a
// beam whose waist sits on the HOE and whose Rayleigh range is short is already near its
// beam-parameter-product limit there (docs/seed-reproduction.md, "The pixel-beam model").
#include <QtTest>

#include <algorithm>
#include <cmath>

#include "app/embedded_scene.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/lens_catalog.h"
#include "model/scene/scene_io.h"

namespace tst_pixel_beam_gain {

using namespace fovea;

namespace {
Scene withBeam(double waist_distance_mm, double waist_fwhm_um, double divergence_mrad) {
  Scene s = embeddedDefaultScene();
  s.projector.pixel_beam.waist_distance_mm = waist_distance_mm;
  s.projector.pixel_beam.waist_fwhm_um = waist_fwhm_um;
  s.projector.pixel_beam.divergence_mrad = divergence_mrad;
  return s;
}
// The catalogue lenses that win the cases below on the whole catalogue at 3 starts (the
// search is per lens, so the others cannot change the best; checked with fovea-cli
// optimize-lens --starts 3 on the full catalogue): a quarter of the work.
std::vector<StockLens> winners() {
  std::vector<StockLens> out;
  for (const StockLens& l : defaultLensCatalog())
    if (l.part == "LB1471" || l.part == "LA1433" || l.part == "LB1676" || l.part == "LA4874") out.push_back(l);
  return out;
}
// The sweep of docs/seed-reproduction.md ran `optimize-lens --starts 3`: the same here, so
// the gains are the table's to its printed digits.
double gain(const Scene& s, std::optional<double> max_distance_mm = std::nullopt) {
  LensOptimizationOptions o;
  o.starts_per_lens = 3;
  o.max_distance_mm = max_distance_mm;
  const auto r = optimizeBeamShapingLens(s, winners(), o);
  return r.ok() ? r.value->improvement_percent : -1.0;
}
}  // namespace

class TestPixelBeamGain : public QObject {
  Q_OBJECT
 private slots:
  void nearCollimatedBeamIsRefocusedFar() {
    // The default beam (waist 600 um at 150 mm, 1.2 mrad: z_R = 500 mm) is nearly collimated
    // over the 114 mm throw: a 50 mm lens refocuses it to a tenth (docs/analyses.md: 89.7 %).
    const double g = gain(withBeam(150, 600, 1.2));
    QVERIFY2(std::abs(g - 89.7) < 0.05, qPrintable(QString::number(g)));
  }

  void waistOnTheHoeWithShortRayleighRangeLeavesLittleToGain() {
    // Waist on the HOE (114 mm, the throw), 300 um and 12 mrad (z_R = 25 mm): the sweep's
    // smallest gain, 20.6 %, still above the seed's 14 %; at 3 mrad it is back to 64 %
    // (docs/seed-reproduction.md, to the digits printed there).
    const double g = gain(withBeam(114, 300, 12));
    QVERIFY2(std::abs(g - 20.6) < 0.05, qPrintable(QString::number(g)));
    const double h = gain(withBeam(114, 300, 3));
    QVERIFY2(std::abs(h - 64.0) < 0.5, qPrintable(QString::number(h)));
  }

  void lensDistanceBoundIsHonoured() {
    LensOptimizationOptions o;
    o.starts_per_lens = 3;
    o.max_distance_mm = 20.0;
    const auto r = optimizeBeamShapingLens(withBeam(150, 600, 1.2), winners(), o);
    QVERIFY(r.ok());
    QCOMPARE(r.value->distance_bound_mm, 20.0);
    QVERIFY(r.value->best.placement.distance_mm <= 20.0 + 1e-9);
    // A lens kept within 20 mm of the projector still gains 78 % (docs/seed-reproduction.md):
    // the placement limit is not what separates us from the seed's 14 %. The winner is the
    // UV-fused-silica LA4874 (78.29 %), a hair ahead of the N-BK7 LA1433 (78.23 %): both to the
    // digits docs/analyses.md prints.
    QVERIFY2(std::abs(r.value->improvement_percent - 78.29) <= 0.005,
             qPrintable(QString::number(r.value->improvement_percent, 'f', 4)));
    QCOMPARE(r.value->best.lens.part, std::string("LA4874"));
    const auto la1433 = std::find_if(r.value->candidates.begin(), r.value->candidates.end(),
                                     [](const LensCandidateResult& c) { return c.lens.part == "LA1433"; });
    QVERIFY(la1433 != r.value->candidates.end());
    const double la1433_percent = 100.0 * (r.value->rms_before_um - la1433->rms_spot_um) / r.value->rms_before_um;
    QVERIFY2(std::abs(la1433_percent - 78.23) <= 0.005, qPrintable(QString::number(la1433_percent, 'f', 4)));
  }
};

QTEST_APPLESS_MAIN(TestPixelBeamGain)

}  // namespace tst_pixel_beam_gain
#include "tst_pixel_beam_gain.moc"
