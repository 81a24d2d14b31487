// Binocular scenes (issue 30): the "binocular" block of the scene file (loader, writer,
// validator), the monocular scene of each eye (model/scene/eye_scene.h), and mirror symmetry:
// the left eye at a yaw-mirrored gaze gives the right eye's numbers, lateral ones negated;
// mode "explicit" (a left train in the file): loading, round trip, malformed trains refused,
// and a left train equal to the mirror giving mode mirror's numbers.
#include <QtTest>
#include "tests/test_paths.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "model/analysis/analysis_registry.h"
#include "model/analysis/trace_fov.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"
#include "model/scene/eye_scene.h"
#include "model/scene/scene_fields.h"
#include "model/scene/scene_geometry.h"
#include "model/scene/scene_io.h"

namespace tst_eye_scene {

using namespace fovea;

namespace {
std::string readText(const std::string& rel) {
  std::ifstream in(std::string(FOVEA_SOURCE_DIR) + "/" + rel, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
Scene parsedOrFail(const std::string& text, const std::string& source) {
  SceneLoadResult r = parseScene(text, source);
  if (!r.ok()) qFatal("%s: %s", source.c_str(), r.errors.front().c_str());
  return *r.scene;
}
Scene binocularPrototype() {
  return parsedOrFail(readText("resources/scenes/binocular-prototype.json"), "binocular-prototype.json");
}
// The prototype's text with `insert` added as the last top-level key and the version set.
std::string prototypeWith(const std::string& insert, int version = 2) {
  std::string t = readText("resources/scenes/prototype-bench.json");
  t.replace(t.find("\"version\": 1"), 12, "\"version\": " + std::to_string(version));
  const auto end = t.rfind('}');
  return t.substr(0, end - 1) + ",\n  " + insert + "\n}\n";
}
std::vector<std::string> errorsOf(const std::string& text) {
  return parseScene(text, "b.json").errors;
}
std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& e : v) s += e + "\n";
  return s;
}
constexpr double kTol = 1e-12;
constexpr double kEdgesTolDeg = 0.005;  // FovEdgesOptions::tolerance_deg (fov_edges.h)
}  // namespace

class TestEyeScene : public QObject {
  Q_OBJECT
 private slots:
  void exampleLoadsAndRoundTrips() {
    const std::string text = readText("resources/scenes/binocular-prototype.json");
    SceneLoadResult r = parseScene(text, "binocular-prototype.json");
    QVERIFY2(r.ok(), joined(r.errors).c_str());
    QCOMPARE(r.warnings.size(), std::size_t{0});
    QVERIFY(r.scene->binocular.has_value());
    QCOMPARE(r.scene->binocular->mode, std::string("mirror"));
    QCOMPARE(r.scene->binocular->ipd_mm, 63.0);
    QCOMPARE(serializeScene(*r.scene), text);  // canonical: load -> save byte for byte
    QVERIFY(text.find("\"version\": 2,") != std::string::npos);
    // Apart from the block (and the name, the notes and the focus axis, foveal_display z), it is
    // the monocular prototype.
    Scene right = eyeScene(*r.scene, EyeSide::Right);
    Scene proto = parsedOrFail(readText("resources/scenes/prototype-bench.json"), "p");
    right.name = proto.name;
    right.notes = proto.notes;
    QCOMPARE(right.stages.size(), proto.stages.size() + 1);
    QCOMPARE(right.stages[4].element + "." + right.stages[4].axis, std::string("foveal_display.z"));
    right.stages.erase(right.stages.begin() + 4);
    QVERIFY(right == proto);
  }

  void monocularFilesKeepTheirBytes() {
    // The default scene and the seed scene stay version 1, byte for byte, and gain no key.
    for (const char* rel : {"resources/scenes/prototype-bench.json", "resources/scenes/seed-fitted.json"}) {
      const std::string text = readText(rel);
      const Scene s = parsedOrFail(text, rel);
      QVERIFY(!s.binocular.has_value());
      QCOMPARE(serializeScene(s), text);
      QVERIFY(text.find("\"version\": 1,") != std::string::npos);
      QVERIFY(serializeScene(s).find("binocular") == std::string::npos);
      // Made binocular it is version 2 with the block; made monocular again, the same bytes.
      Scene b = s;
      b.binocular = Binocular{};
      const std::string saved = serializeScene(b);
      QVERIFY(saved.find("\"version\": 2,") != std::string::npos);
      QVERIFY(saved.find("\"binocular\": {\n    \"mode\": \"mirror\",\n    \"ipd_mm\": 63.0\n  }\n}\n") !=
              std::string::npos);
      QVERIFY(parsedOrFail(saved, "b") == b);
      b.binocular.reset();
      QCOMPARE(serializeScene(b), text);
    }
  }

  void blockDefaultsAndErrors() {
    // An empty block: mirror, 63 mm.
    Scene s = parsedOrFail(prototypeWith("\"binocular\": {}"), "b.json");
    QVERIFY(s.binocular.has_value());
    QCOMPARE(s.binocular->ipd_mm, 63.0);
    QCOMPARE(s.binocular->mode, std::string("mirror"));
    // Ranges and types through the field table, "FILE: json.path: problem".
    auto errors = errorsOf(prototypeWith("\"binocular\": {\"ipd_mm\": 30}"));
    QCOMPARE(errors.size(), std::size_t{1});
    QCOMPARE(errors[0], std::string("b.json: binocular.ipd_mm: must be in [40, 90], got 30"));
    errors = errorsOf(prototypeWith("\"binocular\": {\"mode\": \"stereo\", \"ipd_mm\": \"63\"}"));
    QCOMPARE(errors.size(), std::size_t{2});
    QCOMPARE(errors[0], std::string("b.json: binocular.mode: must be one of mirror, explicit, got \"stereo\""));
    QCOMPARE(errors[1], std::string("b.json: binocular.ipd_mm: must be a number, got a string"));
    errors = errorsOf(prototypeWith("\"binocular\": [63]"));
    QCOMPARE(errors.size(), std::size_t{1});
    QCOMPARE(errors[0], std::string("b.json: binocular: must be an object, got an array of 1"));
    // A newer version is refused; an unknown key in the block is kept (a warning).
    errors = errorsOf(prototypeWith("\"binocular\": {}", 3));
    QCOMPARE(errors.size(), std::size_t{1});
    QCOMPARE(errors[0], std::string("b.json: version: file is version 3, this studio reads up to version 2 "
                                    "(update the studio)"));
    SceneLoadResult r = parseScene(prototypeWith("\"binocular\": {\"ipd_mm\": 60, \"vertex_mm\": 12}"), "b.json");
    QVERIFY(r.ok());
    QCOMPARE(r.warnings.size(), std::size_t{1});
    QVERIFY(serializeScene(*r.scene).find("\"vertex_mm\": 12") != std::string::npos);
    // The in-memory validator applies the same rules.
    Scene bad = binocularPrototype();
    bad.binocular->ipd_mm = 100;
    const auto v = validateScene(bad);
    QCOMPARE(v.size(), std::size_t{1});
    QCOMPARE(v[0], std::string("binocular.ipd_mm: must be in [40, 90], got 100"));
    // And the sweepable numbers include it (a binocular scene only).
    Scene b = binocularPrototype();
    *std::get<double*>(numberAt(b, "binocular.ipd_mm")) = 58;
    QCOMPARE(b.binocular->ipd_mm, 58.0);
    Scene mono = parsedOrFail(readText("resources/scenes/prototype-bench.json"), "p");
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, numberAt(mono, "binocular.ipd_mm"));
  }

  void eyeScenesAreMirrorImages() {
    const Scene s = binocularPrototype();
    // Right eye's rotation centre at x = 0 (HOE at 0, no lateral offset): mid-plane at -31.5.
    QCOMPARE(midPlaneX(s), -31.5);
    const Scene right = eyeScene(s, EyeSide::Right), left = eyeScene(s, EyeSide::Left);
    QVERIFY(!right.binocular && !left.binocular);
    QCOMPARE(right.projector.pose.position_mm[0], 90.0);
    QCOMPARE(left.projector.pose.position_mm[0], -153.0);  // 2 (-31.5) - 90
    QCOMPARE(left.hoe.pose.position_mm[0], -63.0);
    QCOMPARE(left.foveal_display.pose.position_mm[0], -63.0 - right.foveal_display.pose.position_mm[0]);
    QCOMPARE(left.lens.pose.position_mm[0], -135.0);  // 2 (-31.5) - 72
    QCOMPARE(left.projector.pose.rotation_deg[0], -right.projector.pose.rotation_deg[0]);
    QCOMPARE(left.projector.pose.rotation_deg[1], right.projector.pose.rotation_deg[1]);
    for (std::size_t i = 0; i < s.hoe_layers.size(); ++i) {
      QCOMPARE(left.hoe_layers[i].recording.reference_point_mm[0],
               -63.0 - right.hoe_layers[i].recording.reference_point_mm[0]);
      QCOMPARE(left.hoe_layers[i].recording.signal_point_mm[2], right.hoe_layers[i].recording.signal_point_mm[2]);
    }
    // The eyes' rotation centres are one IPD apart, symmetric about the mid-plane.
    const EyePlacement el = placeEye(left), er = placeEye(right);
    QCOMPARE(er.rotation_center.x() - el.rotation_center.x(), 63.0);
    QCOMPARE(el.rotation_center.z(), er.rotation_center.z());
    // A yaw-mirrored gaze puts the left pupil at the mirror image of the right one.
    const EyePlacement pl = placeEye(left, -15, 7), pr = placeEye(right, 15, 7);
    QVERIFY(std::abs((pl.pupil_center.x() + 31.5) + (pr.pupil_center.x() + 31.5)) < kTol);
    QVERIFY(std::abs(pl.pupil_center.y() - pr.pupil_center.y()) < kTol);
    QVERIFY(std::abs(pl.pupil_center.z() - pr.pupil_center.z()) < kTol);
    // Stages: x and yaw ranges mirrored, the same readings (home offsets kept: centred ranges).
    for (std::size_t i = 0; i < s.stages.size(); ++i) {
      const StageBinding &a = right.stages[i], &b = left.stages[i];
      const bool flips = a.axis == "x" || a.axis == "yaw";
      QCOMPARE(b.soft_limits[0], flips ? -a.soft_limits[1] : a.soft_limits[0]);
      QCOMPARE(b.soft_limits[1], flips ? -a.soft_limits[0] : a.soft_limits[1]);
      QCOMPARE(b.soft_limits[0] - b.home_offset, a.soft_limits[0] - a.home_offset);
    }
    // An off-centre range keeps its stage readings: [-2, 6] from home -12.5 -> [-6, 2] from -16.5.
    Scene off = s;
    off.stages[0].axis = "x";
    off.stages[0].soft_limits = {-2.0, 6.0};
    off.stages[0].home_offset = -12.5;
    const StageBinding m = eyeScene(off, EyeSide::Left).stages[0];
    QCOMPARE(m.soft_limits[0], -6.0);
    QCOMPARE(m.soft_limits[1], 2.0);
    QCOMPARE(m.home_offset, -16.5);
    // Zeros stay +0 (no "-0.0" in a saved scene or a document).
    QVERIFY(!std::signbit(left.eye.gaze_deg[0]) && !std::signbit(left.projector.pose.rotation_deg[2]));
    const std::string saved = serializeScene(left);
    QVERIFY(saved.find("-0.0,") == std::string::npos && saved.find("-0.0\n") == std::string::npos);
    // The left scene is a valid monocular scene; mirroring twice gives the scene back.
    QVERIFY2(validateScene(left).empty(), joined(validateScene(left)).c_str());
    QVERIFY(mirroredScene(mirroredScene(s, -31.5), -31.5) == s);
    // A monocular scene has no eyes to choose from.
    const Scene mono = parsedOrFail(readText("resources/scenes/prototype-bench.json"), "p");
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, eyeScene(mono, EyeSide::Left));
    QCOMPARE(eyeSideFromName("left"), std::optional<EyeSide>(EyeSide::Left));
    QVERIFY(!eyeSideFromName("both"));
  }

  void traceIsMirrorSymmetric() {
    // The left eye at (-yaw, pitch) with the HOE shifted by -x sees what the right eye sees at
    // (yaw, pitch) with +x: ray counts exactly; efficiency, the dense FOV (counted on the ray
    // grid) and the extent to 1e-12 (measured: <= 5e-14 deg). The edge-finding FOV (the
    // default estimator, fov_edges.h) to 1e-8 only: its finite-difference step (h = 1e-5)
    // turns the last-bit rounding of the mirrored coordinates (the left train sits 63 mm
    // away, other magnitudes, other roundings) into up to 2e-10 deg here.
    const Scene s = binocularPrototype();
    const Scene right = eyeScene(s, EyeSide::Right), left = eyeScene(s, EyeSide::Left);
    TracePipeline pr, pl;
    int compared = 0;
    for (const auto& [yaw, pitch, shift] :
         std::vector<std::array<double, 3>>{{0, 0, 0}, {12, 4, 2.0}, {-18, -6, -3.1}, {20, 0, 3.4}}) {
      TraceOptions o;
      o.rays = 4000;
      o.keep_field_rays = true;  // the dense FOV counts them
      o.gaze_deg = std::array<double, 2>{yaw, pitch};
      o.hoe_shift_mm = {shift, 0.0};
      TraceOptions m = o;
      m.gaze_deg = std::array<double, 2>{-yaw, pitch};
      m.hoe_shift_mm = {-shift, 0.0};
      const TraceResult a = pr.run(right, o), b = pl.run(left, m);
      QCOMPARE(b.rays, a.rays);
      QCOMPARE(b.rays_in_pupil, a.rays_in_pupil);
      QCOMPARE(b.rays_efficient, a.rays_efficient);
      QCOMPARE(b.rays_on_hoe, a.rays_on_hoe);
      QVERIFY(a.rays_efficient > 1000);
      QVERIFY2(std::abs(b.mean_efficiency - a.mean_efficiency) < kTol,
               qPrintable(QString::number(b.mean_efficiency - a.mean_efficiency)));
      const TraceFov fa = traceFov(right, a, o), fb = traceFov(left, b, m);
      const auto close = [](const FovDeg& x, const FovDeg& y, double tol) {
        return std::abs(x.horizontal - y.horizontal) < tol && std::abs(x.vertical - y.vertical) < tol &&
               std::abs(x.diagonal - y.diagonal) < tol;
      };
      QVERIFY2(
          close(fa.dense, fb.dense, kTol),
          qPrintable(QString("%1 vs %2").arg(fa.dense.horizontal, 0, 'g', 17).arg(fb.dense.horizontal, 0, 'g', 17)));
      QVERIFY(close(fa.extent, fb.extent, kTol));
      QVERIFY2(close(fa.exact, fb.exact, 1e-8),
               qPrintable(QString("%1 vs %2").arg(fa.exact.vertical, 0, 'g', 17).arg(fb.exact.vertical, 0, 'g', 17)));
      QVERIFY(fa.dense.horizontal > 80.0 && fa.dense.vertical > 70.0);  // the prototype's ~90 x 78 deg
      ++compared;
    }
    QCOMPARE(compared, 4);
  }

  void sweepIsMirrorSymmetric() {
    // The gaze sweep (fovea-cli sweep's analysis): the left eye's sample at -g is the right
    // eye's at +g with the FOV-maximising HOE shift and the pupil's lateral position (about
    // the mid-plane x = -31.5) negated. Dense FOV: everything to 1e-12 (measured: equal). The
    // default edge-finding FOV: the shifts, plateaus, efficiency and eye box to 1e-12, the FOV
    // itself only to the estimator's own tolerance (FovEdgesOptions::tolerance_deg, 0.005 deg):
    // its bisections approach a mirrored edge from the other side and stop at another point
    // of the same 0.005 deg bracket (measured: 0.0032 deg at 15 deg gaze).
    const Scene s = binocularPrototype();
    const auto* def = analysis::findAnalysisDefinition("sweep");
    QVERIFY(def);
    std::array<double, 2> worst{0, 0};  // dense, edges: the largest FOV difference (deg)
    for (const char* method : {"dense", "edges"}) {
      nlohmann::json v = analysis::defaultValues(*def);
      v["gaze-from"] = -15.0;
      v["gaze-to"] = 15.0;
      v["gaze-step"] = 15.0;
      v["rays"] = 1500;
      v["fov-method"] = method;
      const bool dense = std::string(method) == "dense";
      const auto a = def->run(eyeScene(s, EyeSide::Right), v, {});
      const auto b = def->run(eyeScene(s, EyeSide::Left), v, {});
      QVERIFY(a && b);
      const auto& sa = (*a)["samples"];
      const auto& sb = (*b)["samples"];
      QCOMPARE(sa.size(), std::size_t{3});
      QCOMPARE(sb.size(), sa.size());
      auto near = [](const nlohmann::json& p, const nlohmann::json& q, double sign, double tol) {
        return std::abs(p.get<double>() - sign * q.get<double>()) < tol;
      };
      for (std::size_t i = 0; i < sa.size(); ++i) {
        const auto& x = sa[i];
        const auto& y = sb[sa.size() - 1 - i];
        QCOMPARE(y["gaze_deg"].get<double>(), -x["gaze_deg"].get<double>());
        QVERIFY2(
            near(y["hoe_shift_mm"], x["hoe_shift_mm"], -1, kTol),
            qPrintable(QString("%1 vs %2").arg(y["hoe_shift_mm"].dump().c_str(), x["hoe_shift_mm"].dump().c_str())));
        for (int k = 0; k < 2; ++k) QVERIFY(near(y["shift_plateau_mm"][1 - k], x["shift_plateau_mm"][k], -1, kTol));
        for (const char* k : {"horizontal", "vertical", "diagonal"}) {
          worst[dense ? 0 : 1] =
              std::max(worst[dense ? 0 : 1], std::abs(y["fov_deg"][k].get<double>() - x["fov_deg"][k].get<double>()));
          QVERIFY2(near(y["fov_deg"][k], x["fov_deg"][k], 1, dense ? kTol : kEdgesTolDeg), k);
        }
        QVERIFY(near(y["mean_efficiency"], x["mean_efficiency"], 1, kTol));
        // Lateral positions about the mid-plane: x - x_m negated.
        QVERIFY(std::abs((y["pupil_position_mm"].get<double>() + 31.5) +
                         (x["pupil_position_mm"].get<double>() + 31.5)) < kTol);
      }
      QVERIFY(std::abs(sa[2]["hoe_shift_mm"].get<double>()) > 1.0);  // 15 deg needs the HOE moved
      QVERIFY(std::abs((*a)["eyebox_mm"].get<double>() - (*b)["eyebox_mm"].get<double>()) < kTol);
    }
    qInfo("largest FOV difference between the mirrored eyes: dense %.3g deg, edges %.3g deg", worst[0], worst[1]);
  }

  void explicitLeftTrainLoadsAndRoundTrips() {
    const Scene mirror = binocularPrototype();
    const Scene expl = explicitBinocularScene(mirror);
    QCOMPARE(expl.binocular->mode, std::string("explicit"));
    QVERIFY(expl.binocular->left.has_value());
    const std::string text = serializeScene(expl);
    QVERIFY(text.find("\"mode\": \"explicit\"") != std::string::npos && text.find("\"left\": {") != std::string::npos);
    QVERIFY(text.find("\"version\": 2,") != std::string::npos);
    // Loads as written, without warnings, and saves byte for byte.
    SceneLoadResult r = parseScene(text, "explicit.json");
    QVERIFY2(r.ok(), joined(r.errors).c_str());
    QCOMPARE(r.warnings.size(), std::size_t{0});
    QVERIFY(*r.scene == expl);
    QCOMPARE(serializeScene(*r.scene), text);
    QVERIFY(validateScene(*r.scene).empty());
    // Its eyes: the right one the scene's train, the left one the train as written (here the
    // mirror image, so mode mirror's left eye).
    QVERIFY(eyeScene(*r.scene, EyeSide::Right) == eyeScene(mirror, EyeSide::Right));
    QVERIFY(eyeScene(*r.scene, EyeSide::Left) == eyeScene(mirror, EyeSide::Left));
    // A left train of its own: moved 1 mm and with a thicker layer, the left eye has them.
    Scene own = expl;
    own.binocular->left->hoe.pose.position_mm[0] -= 1.0;
    own.binocular->left->hoe_layers[0].thickness_um = 20.0;
    const Scene reloaded = parsedOrFail(serializeScene(own), "own.json");
    const Scene left = eyeScene(reloaded, EyeSide::Left);
    QCOMPARE(left.hoe.pose.position_mm[0], -64.0);
    QCOMPARE(left.hoe_layers[0].thickness_um, 20.0);
    QCOMPARE(eyeScene(reloaded, EyeSide::Right).hoe_layers[0].thickness_um, mirror.hoe_layers[0].thickness_um);
    // An unknown key inside the left train is kept where it was and becomes the left eye's.
    std::string withKey = serializeScene(expl);
    const auto at = withKey.find("\"left\": {") + std::string("\"left\": {").size();
    withKey.insert(at, "\n      \"comment\": \"as built\",");
    SceneLoadResult k = parseScene(withKey, "k.json");
    QVERIFY2(k.ok(), joined(k.errors).c_str());
    QCOMPARE(k.warnings.size(), std::size_t{1});
    QVERIFY(serializeScene(*k.scene).find("\"comment\": \"as built\"") != std::string::npos);
    QCOMPARE(eyeScene(*k.scene, EyeSide::Left).unknown["/"]["comment"], nlohmann::ordered_json("as built"));
  }

  void malformedLeftTrainIsRefused() {
    const Scene expl = explicitBinocularScene(binocularPrototype());
    const std::string good = serializeScene(expl);
    nlohmann::ordered_json base = nlohmann::ordered_json::parse(good);
    const auto errorsWith = [&](const std::function<void(nlohmann::ordered_json&)>& change) {
      nlohmann::ordered_json j = base;
      change(j);
      return errorsOf(j.dump(2) + "\n");
    };
    // Mode explicit without a left train; a left train in mode mirror.
    auto e = errorsWith([](auto& j) { j["binocular"].erase("left"); });
    QCOMPARE(joined(e), std::string("b.json: binocular.left: missing required field (mode \"explicit\": the left "
                                    "eye's optical train)\n"));
    e = errorsWith([](auto& j) { j["binocular"]["mode"] = "mirror"; });
    QCOMPARE(joined(e), std::string("b.json: binocular.left: a left train needs mode \"explicit\" (mode \"mirror\" "
                                    "derives the left eye's train)\n"));
    e = errorsWith([](auto& j) { j["binocular"]["left"] = 3; });
    QCOMPARE(joined(e), std::string("b.json: binocular.left: must be an object, got a number (3)\n"));
    // A missing element, a missing field, a NaN (JSON null), a value out of range: each named.
    e = errorsWith([](auto& j) { j["binocular"]["left"].erase("eye"); });
    QCOMPARE(joined(e), std::string("b.json: binocular.left.eye: missing required field\n"));
    e = errorsWith([](auto& j) { j["binocular"]["left"]["projector"].erase("fov_deg"); });
    QCOMPARE(joined(e), std::string("b.json: binocular.left.projector.fov_deg: missing required field\n"));
    e = errorsWith([](auto& j) { j["binocular"]["left"]["hoe"]["position_mm"][0] = nullptr; });
    QCOMPARE(joined(e), std::string("b.json: binocular.left.hoe.position_mm[0]: must be a number, got null\n"));
    e = errorsWith([](auto& j) { j["binocular"]["left"]["hoe_layers"][1]["n1"] = nullptr; });
    QCOMPARE(joined(e), std::string("b.json: binocular.left.hoe_layers[1].n1: must be a number, got null\n"));
    Scene nan = expl;
    nan.binocular->left->eye.relief_mm = std::nan("");
    QCOMPARE(joined(validateScene(nan)), std::string("binocular.left.eye.relief_mm: must be a number, got null\n"));
    // Other elements than the scene's train: fewer layers, another stage axis, no stages.
    e = errorsWith([](auto& j) { j["binocular"]["left"]["hoe_layers"].erase(2); });
    QCOMPARE(joined(e), std::string("b.json: binocular.left.hoe_layers: the left train has 2 HOE layer(s), the "
                                    "scene's (right) train 3: both eyes' trains have the same elements\n"));
    e = errorsWith([](auto& j) { j["binocular"]["left"]["hoe_layers"] = nlohmann::ordered_json::array(); });
    QCOMPARE(joined(e), std::string("b.json: binocular.left.hoe_layers: must contain at least one layer\n"));
    e = errorsWith([](auto& j) { j["binocular"]["left"]["stages"][0]["axis"] = "z"; });
    QCOMPARE(e.size(), std::size_t{1});
    QVERIFY2(e[0].rfind("b.json: binocular.left.stages[0]: drives hoe z, the scene's stages[0] hoe x", 0) == 0,
             e[0].c_str());
    e = errorsWith([](auto& j) { j["binocular"]["left"].erase("stages"); });
    QCOMPARE(e.size(), std::size_t{1});
    QVERIFY2(e[0].rfind("b.json: binocular.left.stages: the left train has 0 stage axes, the scene's (right) train ",
                        0) == 0,
             e[0].c_str());
  }

  void explicitMirrorTrainGivesMirrorNumbers() {
    // A left train written out equal to the mirror gives mode mirror's numbers: the trace and
    // the sweep of the left eye (dense FOV) are the same documents.
    const Scene mirror = binocularPrototype();
    const Scene expl = parsedOrFail(serializeScene(explicitBinocularScene(mirror)), "explicit.json");
    const auto* trace = analysis::findAnalysisDefinition("trace");
    const auto* sweep = analysis::findAnalysisDefinition("sweep");
    QVERIFY(trace && sweep);
    nlohmann::json t = analysis::defaultValues(*trace);
    t["rays"] = 2000;
    t["gaze-yaw"] = -12.0;
    t["gaze-pitch"] = 4.0;
    const auto a = trace->run(eyeScene(mirror, EyeSide::Left), t, {});
    const auto b = trace->run(eyeScene(expl, EyeSide::Left), t, {});
    QVERIFY(a && b);
    QCOMPARE(*b, *a);
    QVERIFY((*a)["fov_deg"]["horizontal"].get<double>() > 25.0);  // 29.3 deg: the HOE unshifted at -12 deg
    QVERIFY((*a)["rays_in_pupil"].get<int>() > 500);
    nlohmann::json v = analysis::defaultValues(*sweep);
    v["gaze-from"] = -10.0;
    v["gaze-to"] = 10.0;
    v["gaze-step"] = 10.0;
    v["rays"] = 1000;
    v["fov-method"] = "dense";
    const auto c = sweep->run(eyeScene(mirror, EyeSide::Left), v, {});
    const auto d = sweep->run(eyeScene(expl, EyeSide::Left), v, {});
    QVERIFY(c && d);
    QCOMPARE((*d)["samples"], (*c)["samples"]);
    QCOMPARE((*d)["eyebox_mm"], (*c)["eyebox_mm"]);
    QVERIFY(std::abs((*c)["samples"][0]["hoe_shift_mm"].get<double>()) > 0.5);
  }
};

QTEST_GUILESS_MAIN(TestEyeScene)

}  // namespace tst_eye_scene
#include "tst_eye_scene.moc"
