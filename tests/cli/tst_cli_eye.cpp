// fovea-cli --eye left|right|both on trace, sweep, compare-shift, selectivity, resolution, tolerance,
// fit and retina-image (issue 30;
// app/cli/eye_option.h): a monocular scene's documents unchanged and --eye refused on it; a
// binocular scene's "eyes" with each eye's usual document; mirrored eyes give equal numbers;
// validate on the binocular example and on a bad block.
#include <QtTest>
#include "tests/test_paths.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "model/image/image_io.h"
#include "model/scene/eye_scene.h"
#include "model/scene/scene_io.h"
#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_eye {

namespace {
using fovea::testing::cliText;
const QString kMono = QString(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json";
const QString kBino = QString(FOVEA_SOURCE_DIR) + "/resources/scenes/binocular-prototype.json";

std::set<std::string> keysOf(const nlohmann::json& j) {
  std::set<std::string> k;
  for (auto it = j.begin(); it != j.end(); ++it) k.insert(it.key());
  return k;
}
double num(const nlohmann::json& j) {
  return j.get<double>();
}
QString writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return QString::fromStdString(path.string());
}
// |a - b| <= tol * max(|a|, |b|, 1).
bool near(double a, double b, double tol) {
  return std::abs(a - b) <= tol * std::max({std::abs(a), std::abs(b), 1.0});
}
// A tolerance spec whose one parameter, the HOE's distance along z, is mirror-invariant, over
// the symmetric gazes -10, 0, 10 deg: the mirrored eyes' trials are mirror images.
const char* kMirrorSymmetricSpec = R"({
  "format": "fovea-tolerance",
  "parameters": [{"name": "HOE z", "path": "hoe.position_mm[2]", "distribution": "normal", "sigma": 0.5}],
  "gaze": {"axis": "yaw", "from_deg": -10, "to_deg": 10, "step_deg": 10},
  "compensator": "fixed", "wavelength_nm": 532, "pass": {"fov_min_deg": {"min": 89}},
  "target_yield": 0.9, "fov_tolerance_deg": 0.05
})";
}  // namespace

class TestCliEye : public QObject {
  Q_OBJECT
 private slots:
  void monocularTraceUnchangedAndEyeRefused() {
    const auto mono = cliText({"trace", kMono, "--gaze-deg", "10", "--rays", "1500", "--json"});
    QVERIFY2(mono.code == 0, qPrintable(mono.err));
    const auto j = mono.j();
    QVERIFY(!j.contains("eye") && !j.contains("eyes"));
    for (const char* k : {"fov_deg", "rays", "rays_in_pupil", "mean_efficiency", "gaze_deg", "per_wavelength"})
      QVERIFY2(j.contains(k), k);
    for (const char* eye : {"left", "right", "both"}) {
      const auto r = cliText({"trace", kMono, "--eye", eye, "--json"});
      QCOMPARE(r.code, 2);
      QVERIFY2(r.err.contains(QString("--eye %1: ").arg(eye)) && r.err.contains("monocular scene"), qPrintable(r.err));
      QVERIFY(r.out.isEmpty());
    }
    const auto embedded = cliText({"trace", "-", "--eye", "right", "--json"});
    QCOMPARE(embedded.code, 2);
    QVERIFY2(embedded.err.contains("the embedded scene is a monocular scene"), qPrintable(embedded.err));
    const auto bad = cliText({"trace", kBino, "--eye", "nose", "--json"});
    QCOMPARE(bad.code, 2);
    QVERIFY2(bad.err.contains("--eye"), qPrintable(bad.err));
  }

  void binocularTraceGivesBothEyes() {
    const auto mono = cliText({"trace", kMono, "--gaze-deg", "10,3", "--rays", "1500", "--json"});
    QCOMPARE(mono.code, 0);
    const std::set<std::string> monoKeys = keysOf(mono.j());
    // Default = both; --eye both the same document.
    for (const QStringList& extra : {QStringList{}, QStringList{"--eye", "both"}}) {
      const auto r = cliText(QStringList{"trace", kBino, "--gaze-deg", "10,3", "--rays", "1500", "--json"} + extra);
      QVERIFY2(r.code == 0, qPrintable(r.err));
      const auto j = r.j();
      QVERIFY(j.contains("eyes"));
      QCOMPARE(keysOf(j["eyes"]), (std::set<std::string>{"left", "right"}));
      for (const char* e : {"left", "right"}) QCOMPARE(keysOf(j["eyes"][e]), monoKeys);
      // The top level is the right eye's document (the scene's own train, every monocular key).
      nlohmann::json top = j;
      top.erase("eyes");
      QCOMPARE(top, j["eyes"]["right"]);
      // The right eye is the prototype's train: the monocular numbers.
      QCOMPARE(j["eyes"]["right"], mono.j());
      QCOMPARE(j["eyes"]["left"]["gaze_deg"], nlohmann::json::parse("[10.0, 3.0]"));
      // A conjugate gaze of 10 deg is temporal for the right eye, nasal for the left: they differ.
      QVERIFY(j["eyes"]["left"]["rays_in_pupil"] != j["eyes"]["right"]["rays_in_pupil"] ||
              j["eyes"]["left"]["fov_deg"] != j["eyes"]["right"]["fov_deg"]);
    }
    // Repeated gazes: a list, each entry with both eyes.
    const auto list = cliText({"trace", kBino, "--gaze-deg", "0", "--gaze-deg", "5", "--rays", "1000", "--json"});
    QCOMPARE(list.code, 0);
    const auto l = list.j();
    QVERIFY(l.is_array());
    QCOMPARE(l.size(), std::size_t{2});
    for (const auto& e : l) QVERIFY(e.contains("eyes") && e["eyes"].contains("left") && e.contains("fov_deg"));
    QCOMPARE(num(l[1]["eyes"]["left"]["gaze_deg"][0]), 5.0);
    // Text output names the eyes.
    const auto text = cliText({"trace", kBino, "--rays", "1000"});
    QCOMPARE(text.code, 0);
    QVERIFY2(text.out.contains("left eye: gaze") && text.out.contains("right eye: gaze"), qPrintable(text.out));
  }

  void mirroredEyesGiveEqualNumbers() {
    // The left eye at (-12, 4) deg with the HOE at -2 mm = the right eye at (12, 4) with +2 mm:
    // counts exactly, the dense FOV and the extent to 1e-12; the default edge-finding FOV to
    // its own tolerance, 0.005 deg (its bisections meet a mirrored edge from the other side).
    const QStringList common{"--rays", "3000", "--json"};
    const auto l = cliText(QStringList{"trace", kBino, "--eye", "left", "--gaze-deg", "-12,4", "--hoe-shift-mm", "-2",
                                       "--fov-method", "dense"} +
                           common);
    const auto r = cliText(QStringList{"trace", kBino, "--eye", "right", "--gaze-deg", "12,4", "--hoe-shift-mm", "2",
                                       "--fov-method", "dense"} +
                           common);
    QVERIFY2(l.code == 0 && r.code == 0, qPrintable(l.err + r.err));
    const auto a = l.j(), b = r.j();
    QCOMPARE(a["eye"], nlohmann::json("left"));
    QCOMPARE(b["eye"], nlohmann::json("right"));
    QVERIFY(!a.contains("eyes"));
    QVERIFY(num(b["rays_efficient"]) > 500);
    for (const char* k : {"rays", "rays_in_pupil", "rays_efficient", "rays_on_hoe"}) QCOMPARE(a[k], b[k]);
    for (const char* f : {"fov_deg", "fov_dense_deg", "fov_extent_deg"})
      for (const char* k : {"horizontal", "vertical", "diagonal"})
        QVERIFY2(std::abs(num(a[f][k]) - num(b[f][k])) < 1e-12, f);
    QVERIFY(num(b["fov_deg"]["horizontal"]) > 80.0);  // the prototype's ~90 deg, counted densely
    QVERIFY(std::abs(num(a["mean_efficiency"]) - num(b["mean_efficiency"])) < 1e-12);
    QCOMPARE(num(a["hoe_shift_mm"][0]), -num(b["hoe_shift_mm"][0]));
    const auto le =
        cliText(QStringList{"trace", kBino, "--eye", "left", "--gaze-deg", "-12,4", "--hoe-shift-mm", "-2"} + common);
    const auto re =
        cliText(QStringList{"trace", kBino, "--eye", "right", "--gaze-deg", "12,4", "--hoe-shift-mm", "2"} + common);
    QVERIFY2(le.code == 0 && re.code == 0, qPrintable(le.err + re.err));
    for (const char* k : {"horizontal", "vertical", "diagonal"})
      QVERIFY2(std::abs(num(le.j()["fov_deg"][k]) - num(re.j()["fov_deg"][k])) < 0.005, k);
  }

  void sweepPerEye() {
    // The dense FOV: mirror-exact (the default edge estimator only to its 0.005 deg tolerance).
    const QStringList common = QStringList{"--gaze-from", "-10", "--gaze-to", "10", "--gaze-step", "10"} +
                               QStringList{"--rays", "1500", "--fov-method", "dense", "--no-cache", "--json"};
    const auto mono = cliText(QStringList{"sweep", kMono} + common);
    QVERIFY2(mono.code == 0, qPrintable(mono.err));
    QVERIFY(!mono.j().contains("eyes") && !mono.j().contains("eye"));
    const auto refused = cliText(QStringList{"sweep", kMono, "--eye", "left"} + common);
    QCOMPARE(refused.code, 2);
    QVERIFY2(refused.err.contains("monocular scene"), qPrintable(refused.err));
    const auto both = cliText(QStringList{"sweep", kBino, "--eye", "both"} + common);
    QVERIFY2(both.code == 0, qPrintable(both.err));
    const auto j = both.j();
    const auto& left = j["eyes"]["left"];
    const auto& right = j["eyes"]["right"];
    // Every key of the monocular document, per eye and at the top level.
    std::set<std::string> monoKeys = keysOf(mono.j());
    monoKeys.erase("cached");
    for (const auto& doc : {left, right, j})
      for (const auto& k : monoKeys) QVERIFY2(doc.contains(k), k.c_str());
    QCOMPARE(right["samples"], mono.j()["samples"]);
    // Mirror: the left sample at -g is the right one at +g with the HOE shift negated.
    const auto& sl = left["samples"];
    const auto& sr = right["samples"];
    QCOMPARE(sl.size(), std::size_t{3});
    for (std::size_t i = 0; i < 3; ++i) {
      const auto& x = sr[i];
      const auto& y = sl[2 - i];
      QCOMPARE(num(y["gaze_deg"]), -num(x["gaze_deg"]));
      QVERIFY(std::abs(num(y["hoe_shift_mm"]) + num(x["hoe_shift_mm"])) < 1e-12);
      for (const char* k : {"horizontal", "vertical", "diagonal"})
        QVERIFY(std::abs(num(y["fov_deg"][k]) - num(x["fov_deg"][k])) < 1e-12);
    }
    QVERIFY(std::abs(num(sr[2]["hoe_shift_mm"])) > 0.5);  // a 10 deg gaze needs the HOE moved
    QVERIFY(std::abs(num(left["eyebox_mm"]) - num(right["eyebox_mm"])) < 1e-12);
    // One eye: its document and "eye"; a shard runs one eye only.
    const auto one = cliText(QStringList{"sweep", kBino, "--eye", "left"} + common);
    QCOMPARE(one.code, 0);
    QCOMPARE(one.j()["eye"], nlohmann::json("left"));
    QCOMPARE(one.j()["samples"], left["samples"]);
    const auto shard = cliText({"sweep", kBino, "--shard", "0/2", "--json"});
    QCOMPARE(shard.code, 2);
    QVERIFY2(shard.err.contains("--shard") && shard.err.contains("--eye left or right"), qPrintable(shard.err));
  }

  void otherAnalysesPerEye() {
    const auto cs = cliText({"compare-shift", kBino, "--eye", "right", "--no-cache", "--json"});
    QVERIFY2(cs.code == 0, qPrintable(cs.err));
    QCOMPARE(cs.j()["eye"], nlohmann::json("right"));
    QVERIFY(cs.j().contains("hoe_shift") && cs.j().contains("source_shift"));
    const auto monoCs = cliText({"compare-shift", kMono, "--eye", "both", "--json"});
    QCOMPARE(monoCs.code, 2);
    const auto sel = cliText({"selectivity", kBino, "--json"});
    QVERIFY2(sel.code == 0, qPrintable(sel.err));
    const auto s = sel.j();
    QVERIFY(s.contains("eyes") && s["eyes"].contains("left") && s["eyes"].contains("right"));
    // At the plate centre both eyes' layers see the same angles (mirror images).
    QCOMPARE(s["eyes"]["left"]["layers"].size(), s["eyes"]["right"]["layers"].size());
    for (std::size_t i = 0; i < s["eyes"]["left"]["layers"].size(); ++i)
      QVERIFY(std::abs(num(s["eyes"]["left"]["layers"][i]["nominal_efficiency"]) -
                       num(s["eyes"]["right"]["layers"][i]["nominal_efficiency"])) < 1e-12);
  }

  void resolutionPerEye() {
    const auto mono = cliText({"resolution", kMono, "--gaze-deg", "5", "--json"});
    QVERIFY2(mono.code == 0, qPrintable(mono.err));
    QCOMPARE(cliText({"resolution", kMono, "--eye", "right", "--json"}).code, 2);
    const auto both = cliText({"resolution", kBino, "--gaze-deg", "5", "--json"});
    QVERIFY2(both.code == 0, qPrintable(both.err));
    const auto j = both.j();
    QCOMPARE(keysOf(j["eyes"]["left"]), keysOf(mono.j()));
    QCOMPARE(j["eyes"]["right"], mono.j());            // the right eye is the prototype's train
    QVERIFY(j["eyes"]["left"] != j["eyes"]["right"]);  // 5 deg is temporal for one eye, nasal for the other
  }

  void tolerancePerEye() {
    const auto dir = fovea::testing::testTmpDir("cli_eye");
    const QString spec = writeText(dir / "tol-mirror.json", kMirrorSymmetricSpec);
    const QStringList common{"--spec", spec, "--trials", "8", "--seed", "3", "--json"};
    const auto mono = cliText(QStringList{"tolerance", kMono} + common);
    QVERIFY2(mono.code == 0, qPrintable(mono.err));
    QVERIFY(!mono.j().contains("eyes") && !mono.j().contains("eye"));
    const auto refused = cliText(QStringList{"tolerance", kMono, "--eye", "left"} + common);
    QCOMPARE(refused.code, 2);
    QVERIFY2(refused.err.contains("--eye left: ") && refused.err.contains("monocular scene"), qPrintable(refused.err));
    const auto both = cliText(QStringList{"tolerance", kBino} + common);
    QVERIFY2(both.code == 0, qPrintable(both.err));
    const auto j = both.j();
    QCOMPARE(keysOf(j["eyes"]), (std::set<std::string>{"left", "right"}));
    const auto& left = j["eyes"]["left"];
    const auto& right = j["eyes"]["right"];
    // The right eye is the prototype's train: the monocular numbers (its own scene digest aside).
    for (const char* k : {"nominal", "yield", "figures", "sensitivity", "trials"}) QCOMPARE(right[k], mono.j()[k]);
    QCOMPARE(right["yield"], j["yield"]);
    // Mirrored eyes, a mirror-invariant spec: the same nominal figures and distributions
    // (the edge FOV to its 0.005 deg tolerance; equal seen), the same yield (8 trials, 3 with
    // FOV >= 89 deg).
    QVERIFY(num(right["nominal"]["fov_min_deg"]) > 89.0);
    for (const char* k : {"fov_min_deg", "fov_zero_gaze_deg"}) {
      QVERIFY2(std::abs(num(left["nominal"][k]) - num(right["nominal"][k])) < 0.005, k);
      QVERIFY2(std::abs(num(left["figures"][k]["mean"]) - num(right["figures"][k]["mean"])) < 0.005, k);
    }
    QVERIFY(num(right["figures"]["fov_min_deg"]["std"]) > 0.5);  // the HOE's z moves the FOV
    for (const char* k : {"eyebox_mm", "mean_efficiency"})
      QVERIFY2(near(num(left["nominal"][k]), num(right["nominal"][k]), 1e-12), k);
    QCOMPARE(left["yield"]["passed"], right["yield"]["passed"]);
    QCOMPARE(num(right["yield"]["passed"]), 3.0);
    QVERIFY(left["scene_digest"] != right["scene_digest"]);  // each eye's own train
    // One eye: its document and "eye"; a shard or a Slurm job runs one eye only.
    const auto one = cliText(QStringList{"tolerance", kBino, "--eye", "left"} + common);
    QCOMPARE(one.code, 0);
    QCOMPARE(one.j()["eye"], nlohmann::json("left"));
    QCOMPARE(one.j()["figures"], left["figures"]);
    const auto shard = cliText(QStringList{"tolerance", kBino, "--shard", "0/2"} + common);
    QCOMPARE(shard.code, 2);
    QVERIFY2(shard.err.contains("--shard") && shard.err.contains("--eye left or right"), qPrintable(shard.err));
    const QString job = QString::fromStdString((dir / "tol-job").string());
    const auto slurm = cliText({"tolerance", kBino, "--spec", spec, "--trials", "8", "--slurm", job, "--eye", "left"});
    QVERIFY2(slurm.code == 0, qPrintable(slurm.err));
    QVERIFY(fovea::testing::readFileText(dir / "tol-job" / "tolerance.sbatch").find(" --eye left --trials 8") !=
            std::string::npos);
    QCOMPARE(cliText({"tolerance", kBino, "--spec", spec, "--slurm", job}).code, 2);
  }

  void fitPerEye() {
    const auto dir = fovea::testing::testTmpDir("cli_eye");
    const QString targets = writeText(dir / "fit-targets.json", R"({"format": "fovea-fit-targets", "version": 1,
      "targets": [
        {"id": "fov-h", "observable": "fov_deg", "shift": "none", "wavelength_nm": 532, "value": 89.5, "sigma": 0.05},
        {"id": "eff", "observable": "mean_efficiency", "shift": "none", "wavelength_nm": 532, "value": 0.76,
         "sigma": 0.002}]})");
    const QStringList common{"--targets",   targets, "--free", "hoe_layers[1].n1=+-0.004", "--starts", "1",
                             "--max-evals", "30",    "--json"};
    QCOMPARE(cliText(QStringList{"fit", kMono, "--eye", "right"} + common).code, 2);
    const auto both = cliText(QStringList{"fit", kBino} + common);
    QVERIFY2(both.code == 0, qPrintable(both.err));
    const auto j = both.j();
    const auto& left = j["eyes"]["left"];
    const auto& right = j["eyes"]["right"];
    QCOMPARE(j["parameters"], right["parameters"]);
    // Mirrored eyes at gaze 0: the same fit (n1 0.015 -> 0.014658, the efficiency target met).
    const double n1 = num(right["parameters"][0]["fitted"]);
    QVERIFY2(n1 > 0.0145 && n1 < 0.0148, qPrintable(QString::number(n1, 'g', 10)));
    QVERIFY2(near(num(left["parameters"][0]["fitted"]), n1, 1e-9), qPrintable(QString::fromStdString(j.dump())));
    QVERIFY(near(num(left["parameters"][0]["uncertainty"]), num(right["parameters"][0]["uncertainty"]), 1e-6));
    QVERIFY(near(num(left["chi2"]), num(right["chi2"]), 1e-9));
    for (std::size_t i = 0; i < 2; ++i)
      QVERIFY(near(num(left["targets"][i]["model"]), num(right["targets"][i]["model"]), 1e-9));
    QVERIFY(std::abs(num(right["targets"][1]["model"]) - 0.76) < 1e-4);
    // --write-scene: the scene's own (right) train only; the binocular block kept.
    const QString out = QString::fromStdString((dir / "fitted-bino.json").string());
    const auto leftWrite = cliText(QStringList{"fit", kBino, "--eye", "left", "--write-scene", out} + common);
    QCOMPARE(leftWrite.code, 2);
    QVERIFY2(leftWrite.err.contains("--write-scene") && leftWrite.err.contains("--eye right"),
             qPrintable(leftWrite.err));
    const auto rightWrite = cliText(QStringList{"fit", kBino, "--eye", "right", "--write-scene", out} + common);
    QVERIFY2(rightWrite.code == 0, qPrintable(rightWrite.err));
    QCOMPARE(rightWrite.j()["eye"], nlohmann::json("right"));
    const auto written = nlohmann::json::parse(fovea::testing::readFileText(out.toStdString()));
    QCOMPARE(written["binocular"]["mode"], nlohmann::json("mirror"));
    QVERIFY(near(num(written["hoe_layers"][1]["n1"]), n1, 1e-12));
  }

  void retinaImagePerEye() {
    const auto dir = fovea::testing::testTmpDir("cli_eye");
    const auto image = dir / "uniform.png";
    fovea::image::writeLinearRgb(image.string(), cv::Mat(277, 480, CV_32FC3, cv::Scalar(0.2, 0.2, 0.2)));
    const QString img = QString::fromStdString(image.string());
    const auto out = [&](const char* name) { return QString::fromStdString((dir / name).string()); };
    const QStringList common{"--image", img, "--rays", "2000", "--json"};
    QCOMPARE(cliText(QStringList{"retina-image", kMono, "--out", out("m.png"), "--eye", "left"} + common).code, 2);
    std::filesystem::remove(dir / "both-left.png");
    const auto both =
        cliText(QStringList{"retina-image", kBino, "--out", out("both.png"), "--gaze-deg", "5,2"} + common);
    QVERIFY2(both.code == 0, qPrintable(both.err));
    const auto j = both.j();
    QCOMPARE(keysOf(j["eyes"]), (std::set<std::string>{"left", "right"}));
    // The right eye's image at --out, the left eye's beside it.
    QCOMPARE(j["eyes"]["right"]["image_out"], nlohmann::json(out("both.png").toStdString()));
    QCOMPARE(j["eyes"]["left"]["image_out"], nlohmann::json(out("both-left.png").toStdString()));
    QCOMPARE(fovea::image::readLinearRgb((dir / "both-left.png").string()).cols, 480);
    // Mirrored eyes: the left eye at (-5, 2) deg is the right one at (5, 2): the line-of-sight
    // spots to 1e-9, the power of a uniform image to 1e-6 (the canvas' pixel grid).
    const auto l = cliText(
        QStringList{"retina-image", kBino, "--eye", "left", "--out", out("l.png"), "--gaze-deg", "-5,2"} + common);
    QVERIFY2(l.code == 0, qPrintable(l.err));
    const auto a = l.j();
    const auto& b = j["eyes"]["right"];
    QCOMPARE(a["eye"], nlohmann::json("left"));
    QCOMPARE(a["rays_in_pupil"], b["rays_in_pupil"]);
    QVERIFY(num(b["rays_in_pupil"]) > 1000);
    for (const char* d : {"peripheral", "foveal"})
      for (const char* k : {"spot_fwhm_arcmin", "cpd_mtf50", "cpd_mtf10"})
        QVERIFY2(near(num(a[d][k]), num(b[d][k]), 1e-9), k);
    QVERIFY(num(b["foveal"]["cpd_mtf50"]) > 10.0);
    QVERIFY(near(num(a["power_in_pupil"]), num(b["power_in_pupil"]), 1e-6));
    QVERIFY(num(b["power_in_pupil"]) > 0);
  }

  void validateBinocularScenes() {
    const auto ok = cliText({"validate", kBino});
    QVERIFY2(ok.code == 0, qPrintable(ok.err));
    QVERIFY2(ok.out.contains("binocular (mirror, IPD 63 mm)"), qPrintable(ok.out));
    const auto dir = fovea::testing::testTmpDir("cli_eye");
    std::ifstream in(kBino.toStdString());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("\"ipd_mm\": 63.0"), 14, "\"ipd_mm\": 120");
    const auto bad = dir / "bad-ipd.json";
    std::ofstream(bad) << text;
    const auto r = cliText({"validate", QString::fromStdString(bad.string())});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.out.contains("bad-ipd.json: binocular.ipd_mm: must be in [40, 90], got 120"), qPrintable(r.out));
  }

  void explicitLeftTrainValidatesAndTraces() {
    // Binocular mode "explicit": a left train written out equal to the mirror validates and
    // gives mode mirror's numbers for both eyes; a malformed left train is refused by name.
    const auto dir = fovea::testing::testTmpDir("cli_eye");
    const auto loaded = fovea::loadSceneFile(kBino.toStdString());
    QVERIFY(loaded.ok());
    const fovea::Scene expl = fovea::explicitBinocularScene(*loaded.scene);
    const QString path = writeText(dir / "explicit.json", fovea::serializeScene(expl));
    const auto ok = cliText({"validate", path});
    QVERIFY2(ok.code == 0, qPrintable(ok.out + ok.err));
    QVERIFY2(ok.out.contains("binocular (explicit, IPD 63 mm)"), qPrintable(ok.out));
    const QStringList common{"--gaze-deg", "-12,4", "--rays", "1500", "--json"};
    const auto a = cliText(QStringList{"trace", kBino} + common);
    const auto b = cliText(QStringList{"trace", path} + common);
    QVERIFY2(a.code == 0 && b.code == 0, qPrintable(a.err + b.err));
    QCOMPARE(b.j(), a.j());  // both eyes, every number
    QVERIFY(b.j()["eyes"]["left"] != b.j()["eyes"]["right"]);
    fovea::Scene bad = expl;
    bad.binocular->left->hoe.size_mm[1] = std::nan("");
    const QString badPath = writeText(dir / "explicit-bad.json", fovea::serializeScene(bad));
    const auto r = cliText({"validate", badPath});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.out.contains("explicit-bad.json: binocular.left.hoe.size_mm[1]: must be a number, got null"),
             qPrintable(r.out));
    QCOMPARE(cliText(QStringList{"trace", badPath} + common).code, 1);
  }

  void closedLoopTakesTheScenesIpd() {
    // closed-loop --binocular on a binocular scene: the scene's IPD unless --ipd is given.
    const auto dir = fovea::testing::testTmpDir("cli_eye");
    std::ifstream in(kBino.toStdString());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("\"ipd_mm\": 63.0"), 14, "\"ipd_mm\": 58.0");
    const auto scene = dir / "ipd58.json";
    std::ofstream(scene) << text;
    const QString path = QString::fromStdString(scene.string());
    const QStringList common{"--binocular", "--fixations", "1", "--fps", "60", "--seed", "4", "--json"};
    const auto fromScene = cliText(QStringList{"closed-loop", path} + common, 300000);
    QVERIFY2(fromScene.code == 0, qPrintable(fromScene.err));
    QCOMPARE(num(fromScene.j()["vergence"]["ipd_mm"]), 58.0);
    QCOMPARE(fromScene.j()["vergence"]["ipd_source"], nlohmann::json("scene"));
    QCOMPARE(fromScene.j()["fixations"].size(), std::size_t{1});
    const auto given = cliText(QStringList{"closed-loop", path, "--ipd", "66"} + common, 300000);
    QVERIFY2(given.code == 0, qPrintable(given.err));
    QCOMPARE(num(given.j()["vergence"]["ipd_mm"]), 66.0);
    QCOMPARE(given.j()["vergence"]["ipd_source"], nlohmann::json("--ipd"));
  }
};

QTEST_GUILESS_MAIN(TestCliEye)

}  // namespace tst_cli_eye
#include "tst_cli_eye.moc"
