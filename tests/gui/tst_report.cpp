// `fovea-cli report` (driving `fovea-studio --report`): the PDF's page count and embedded
// images checked with poppler-utils (pdfinfo, pdfimages -list) against the manifest, the
// self-contained HTML's base64 images decoded, the gaze figures' ray fans counted (manifest
// and pixels against the plain top view), a binocular scene's "Both eyes" section and manifest
// "eyes", and the argument / scene errors' exit codes.
#include <QtTest>
#include "tests/test_paths.h"

#include <QImage>
#include <QProcess>
#include <QRegularExpression>
#include <QStandardPaths>

#include <cmath>

#include <nlohmann/json.hpp>

#include "app/embedded_scene.h"
#include "app/studio/report_tolerance.h"
#include "tests/tolerance_test_spec.h"
#include "viz/efficiency_colors.h"
#include "widgets/analyses/analysis_catalog.h"

namespace tst_report {

namespace {

QString tmpDir() {
  const QString d = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp") + "/gui_report";
  QDir().mkpath(d);
  return d;
}

struct Run {
  int code = -1;
  QString out, err;
};

Run run(const QString& program, const QStringList& args, int timeoutMs = 240000) {
  QProcess p;
  p.start(program, args);
  Run r;
  if (!p.waitForFinished(timeoutMs)) {
    p.kill();
    p.waitForFinished();
    r.err = "timed out";
    return r;
  }
  r.code = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
  r.out = QString::fromUtf8(p.readAllStandardOutput());
  r.err = QString::fromUtf8(p.readAllStandardError());
  return r;
}

QString tool(const char* name) {
  const QString path = QStandardPaths::findExecutable(name);
  if (path.isEmpty()) qFatal("%s not found: install poppler-utils (scripts/install-deps.sh)", name);
  return path;
}

// Figures the report makes for `gazes` chosen gazes: 4 standard 3-D views, per gaze the bench
// with its ray fans, the retina view and the retina map, the retinal image (issue 29) and the 7
// plots (FOV and travel vs gaze, efficiency vs angle and vs wavelength, resolution vs eccentricity
// and vs accommodation, Kogelnik vs RCWA).
int expectedFigures(int gazes) {
  return 4 + gazes * 3 + 1 + 7;
}

// Pixels of `withRays` that differ from `plain` and carry an efficiency colour of the ramp
// (viz::efficiencyColor over [0.1, 1], within a small anti-aliasing tolerance), left of the
// colour bar (which starts at 90 % of the width).
int efficiencyPixelsAdded(const QImage& plain, const QImage& withRays) {
  std::vector<QRgb> ramp;
  for (int i = 0; i <= 200; ++i) {
    const auto c =
        fovea::viz::efficiencyColor(fovea::viz::kLowEfficiency + (1.0 - fovea::viz::kLowEfficiency) * i / 200);
    ramp.push_back(qRgb(int(std::lround(c[0] * 255)), int(std::lround(c[1] * 255)), int(std::lround(c[2] * 255))));
  }
  const QImage a = plain.convertToFormat(QImage::Format_RGB32), b = withRays.convertToFormat(QImage::Format_RGB32);
  if (a.size() != b.size()) return -1;
  int n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width() * 88 / 100; ++x) {
      const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
      if (std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) + std::abs(qBlue(p) - qBlue(q)) <= 48) continue;
      for (QRgb r : ramp)
        if (std::abs(qRed(r) - qRed(q)) + std::abs(qGreen(r) - qGreen(q)) + std::abs(qBlue(r) - qBlue(q)) <= 24) {
          ++n;
          break;
        }
    }
  return n;
}

// The manifest's record of one gaze figure is consistent: rays drawn, some into the pupil,
// in-pupil + missing never more than drawn, the fans changing many pixels.
void checkGazeFigure(const nlohmann::json& g) {
  const int drawn = g["rays_drawn"].get<int>(), in = g["rays_in_pupil"].get<int>();
  const int missing = g["rays_missing"].get<int>(), low = g["rays_low"].get<int>();
  QVERIFY2(drawn > 0, g.dump().c_str());
  QVERIFY2(in > 0, g.dump().c_str());
  QVERIFY2(in + missing <= drawn && low <= drawn, g.dump().c_str());
  QVERIFY2(g["overlay_pixels"].get<int>() > 10 * drawn, g.dump().c_str());  // every ray is a line, not a dot
  QVERIFY2(g["retina_cells"].get<int>() > 0, g.dump().c_str());
}

}  // namespace

class TestReport : public QObject {
  Q_OBJECT
 private slots:
  void pdfHasItsPagesAndImages() {
    const QString pdf = tmpDir() + "/prototype-report.pdf";
    QFile::remove(pdf);
    const Run r =
        run(FOVEA_CLI_PATH, {"report", "", "--out", pdf, "--gaze-deg", "0", "10,0", "--rays", "300", "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const nlohmann::json m = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(QString::fromStdString(m["format"].get<std::string>()), QString("pdf"));
    QVERIFY(m["problems"].empty());
    const int figures = m["figures"].get<int>();
    const int pages = m["pages"].get<int>();
    QCOMPARE(figures, expectedFigures(2));
    QCOMPARE(m["gaze_figures"].size(), std::size_t(2));
    for (const auto& g : m["gaze_figures"]) {
      checkGazeFigure(g);
      QCOMPARE(g["hoe_shift_mm"][0].get<double>(), 0.0);  // the plate stays put without --follow-gaze
    }

    const Run info = run(tool("pdfinfo"), {pdf});
    QCOMPARE(info.code, 0);
    const auto pm = QRegularExpression("Pages:\\s+(\\d+)").match(info.out);
    QVERIFY(pm.hasMatch());
    QCOMPARE(pm.captured(1).toInt(), pages);
    // Title page + key numbers + at least two figures per page after them.
    QVERIFY2(pages >= 2 + (figures + 1) / 2 && pages <= 2 + figures, qPrintable(QString::number(pages)));
    QVERIFY(info.out.contains("Design report"));

    const Run images = run(tool("pdfimages"), {"-list", pdf});
    QCOMPARE(images.code, 0);
    int count = 0, large = 0;
    for (const QString& line : images.out.split('\n')) {
      const QStringList f = line.simplified().split(' ');
      if (f.size() < 5 || f[2] != "image") continue;
      ++count;
      if (f[3].toInt() >= 600 && f[4].toInt() >= 300) ++large;
    }
    QCOMPARE(count, figures);  // one image per figure, none split over two pages
    QCOMPARE(large, figures);  // and every one at print resolution

    // The pages render (poppler can rasterise the first two).
    const Run ppm = run(tool("pdftoppm"), {"-png", "-r", "40", "-f", "1", "-l", "2", pdf, tmpDir() + "/page"});
    QCOMPARE(ppm.code, 0);
    QVERIFY(!QImage(tmpDir() + "/page-01.png").isNull() || !QImage(tmpDir() + "/page-1.png").isNull());
  }

  void htmlIsSelfContained() {
    const QString html = tmpDir() + "/prototype-report.html";
    const Run r = run(FOVEA_CLI_PATH, {"report", "", "--out", html, "--gaze-deg", "0", "5,2", "--rays", "300",
                                       "--follow-gaze", "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const nlohmann::json m = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(m["pages"].is_null());
    QCOMPARE(m["gaze_figures"].size(), std::size_t(2));
    for (const auto& g : m["gaze_figures"]) checkGazeFigure(g);
    // HOE follows gaze: no travel at gaze 0, some at 5 deg yaw and 2 deg pitch.
    QCOMPARE(m["gaze_figures"][0]["hoe_shift_mm"][0].get<double>(), 0.0);
    QVERIFY(std::abs(m["gaze_figures"][1]["hoe_shift_mm"][0].get<double>()) > 0.0);
    QFile f(html);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(f.readAll());
    QVERIFY(text.startsWith("<!DOCTYPE html>"));
    static const QRegularExpression img("<figure id='([^']+)'><img src='data:image/png;base64,([A-Za-z0-9+/=]+)'");
    int n = 0;
    QMap<QString, QImage> byId;
    for (auto it = img.globalMatch(text); it.hasNext();) {
      const auto match = it.next();
      const QImage decoded = QImage::fromData(QByteArray::fromBase64(match.captured(2).toLatin1()), "PNG");
      QVERIFY(!decoded.isNull() && decoded.width() >= 300);
      byId[match.captured(1)] = decoded;
      ++n;
    }
    QCOMPARE(n, m["figures"].get<int>());
    QCOMPARE(n, expectedFigures(2));
    // Gaze 0 is the scene's own gaze: its figure is the plain top view plus the ray fans.
    QVERIFY(byId.contains("view-top") && byId.contains("gaze-1") && byId.contains("retina-view-1"));
    QVERIFY(byId.contains("retina-image") && byId.contains("plot:resolution-vs-accommodation"));
    const int added = efficiencyPixelsAdded(byId["view-top"], byId["gaze-1"]);
    const int drawn = m["gaze_figures"][0]["rays_drawn"].get<int>();
    QVERIFY2(added > 10 * drawn, qPrintable(QString("%1 efficiency pixels for %2 rays").arg(added).arg(drawn)));
    QCOMPARE(efficiencyPixelsAdded(byId["view-top"], byId["view-top"]), 0);
    QVERIFY(!text.contains("src='figure-"));  // nothing outside the file
    QVERIFY(text.contains("Figure 1.") && text.contains("Key numbers") && text.contains("Scene summary"));
    QVERIFY(text.contains("Eye box"));
  }

  // The Tolerance section from a tolerance result: the yield with its interval, the spec table
  // (every tolerance and the width it may take), the yield plot, one histogram per figure and the
  // ranking with its table, in HTML and PDF.
  void toleranceSectionInHtmlAndPdf() {
    const QString spec = tmpDir() + "/tol-spec.json";
    QFile sf(spec);
    QVERIFY(sf.open(QIODevice::WriteOnly));
    sf.write(fovea::testing::smallToleranceSpec());
    sf.close();
    const fovea::Scene scene = fovea::embeddedDefaultScene();
    fovea::widgets::AnalysisParams p = fovea::widgets::defaultParameters(*fovea::widgets::findAnalysis("tolerance"));
    p["spec"] = spec;
    p["trials"] = 20;
    const auto r = fovea::widgets::runAnalysis("tolerance", scene, p);
    QVERIFY(r.has_value());
    fovea::studio::ReportContent c;
    c.title = "Tolerance report";
    c.sceneName = "prototype";
    c.created = QDateTime::currentDateTime();
    c.sections << fovea::studio::toleranceReportSection(*r, fovea::widgets::DisplayUnits{});
    QCOMPARE(c.sections[0].heading, QString("Tolerance"));
    QCOMPARE(c.figureCount(), 7);  // yield, ranking, five histograms
    const QString yield = QString::number(100 * (*r)["yield"]["value"].get<double>(), 'f', 1) + " %";
    QVERIFY2(c.sections[0].introHtml.contains(yield), qPrintable(c.sections[0].introHtml));
    QVERIFY(c.sections[0].introHtml.contains("gaze tracker") && c.sections[0].introHtml.contains("uniform, ± 1.5"));
    QVERIFY(fovea::studio::toleranceReportSection(nlohmann::json{{"format", "other"}}, {}).figures.isEmpty());
    const QString html = tmpDir() + "/tolerance-report.html", pdf = tmpDir() + "/tolerance-report.pdf";
    QString error;
    QVERIFY2(fovea::studio::writeReport(c, html, &error), qPrintable(error));
    int pages = 0;
    QVERIFY2(fovea::studio::writeReport(c, pdf, &error, &pages), qPrintable(error));
    QVERIFY(pages >= 4);  // the intro and seven figures, at most two per page
    QFile hf(html);
    QVERIFY(hf.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(hf.readAll());
    QVERIFY(text.contains("<h2>Tolerance</h2>"));
    QCOMPARE(text.count("<figure id='plot:tolerance-"), 7);
    QVERIFY(text.contains("<th>total index</th>"));  // the ranking table under its figure
    const Run t = run(tool("pdftotext"), {pdf, "-"});
    QCOMPARE(t.code, 0);
    QVERIFY2(t.out.contains("Tolerance") && t.out.contains("Wilson") && t.out.contains("HOE x"), qPrintable(t.out));
  }

  // A binocular scene (issue 30): by default the right eye's report plus the "Both eyes" section and
  // the manifest's "eyes", each eye's FOV, efficiency and x_p at the chosen gazes; mirrored gazes
  // give mirrored numbers. --eye on a monocular scene is refused before the studio starts.
  void binocularReportHasBothEyes() {
    const QString bino = QString(FOVEA_SOURCE_DIR) + "/resources/scenes/binocular-prototype.json";
    const QString html = tmpDir() + "/binocular-report.html";
    const Run r = run(FOVEA_CLI_PATH,
                      {"report", bino, "--out", html, "--gaze-deg=-10", "--gaze-deg", "10", "--rays", "100", "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const nlohmann::json m = nlohmann::json::parse(r.out.toStdString());
    QVERIFY2(m["problems"].empty(), r.out.toUtf8().constData());
    QVERIFY(!m.contains("eye"));
    QCOMPARE(m["sections"][0], nlohmann::json("Both eyes"));
    QCOMPARE(m["figures"].get<int>(), expectedFigures(2));  // the section is a table, no figure
    const auto& left = m["eyes"]["left"]["gazes"];
    const auto& right = m["eyes"]["right"]["gazes"];
    QCOMPARE(left.size(), std::size_t(2));
    QCOMPARE(right.size(), std::size_t(2));
    QCOMPARE(left[0]["gaze_deg"], nlohmann::json({-10.0, 0.0}));
    // The left eye at -10 deg is the right eye at +10 deg: the FOV to the edge finder's 0.005 deg
    // (1e-11 seen), x_p negated (1.638 mm; 1.489 mm at the other, nasal, gaze), efficiencies equal.
    for (int i = 0; i < 2; ++i) {
      const auto& a = left[i];
      const auto& b = right[1 - i];
      for (const char* k : {"horizontal", "vertical", "diagonal"})
        QVERIFY2(std::abs(a["fov_deg"][k].get<double>() - b["fov_deg"][k].get<double>()) < 0.005, k);
      QVERIFY(std::abs(a["x_p_mm"][0].get<double>() + b["x_p_mm"][0].get<double>()) < 1e-9);
      QVERIFY(std::abs(a["mean_efficiency"].get<double>() - b["mean_efficiency"].get<double>()) < 1e-12);
      QCOMPARE(a["hoe_shift_mm"][0].get<double>(), 0.0);  // x_p applied only with --follow-gaze
    }
    QVERIFY(right[1]["fov_deg"]["horizontal"].get<double>() > 80.0);
    const double xp = right[1]["x_p_mm"][0].get<double>();
    QVERIFY2(xp > 1.5 && xp < 1.8, qPrintable(QString::number(xp)));
    QVERIFY(std::abs(std::abs(right[0]["x_p_mm"][0].get<double>()) - xp) > 0.05);  // temporal != nasal
    QFile f(html);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(f.readAll());
    QVERIFY(text.contains("<h2>Both eyes</h2>") && text.contains("IPD 63 mm"));
    QVERIFY(text.contains("<td>left</td>") && text.contains("<td>right</td>"));
    QVERIFY(text.contains("the left eye's its mirror image about the mid-plane"));
    // Each eye's eye box: the left eye's own sweep, equal to the right eye's for mirrored trains
    // (and the key numbers' eye box: the right eye's).
    const double lbox = m["eyes"]["left"]["eyebox_mm"].get<double>(),
                 rbox = m["eyes"]["right"]["eyebox_mm"].get<double>();
    qInfo("eye box: left %.12g mm, right %.12g mm", lbox, rbox);
    // docs/analyses.md prints 7.866 mm.
    QVERIFY2(std::abs(rbox - 7.866) <= 0.0005 && std::abs(lbox - rbox) < 1e-9,
             qPrintable(QString("%1 %2").arg(lbox).arg(rbox)));
    QVERIFY2(text.contains(
                 QString("left eye <b>%1 mm</b>, right eye <b>%2 mm</b>").arg(lbox, 0, 'g', 4).arg(rbox, 0, 'g', 4)),
             qPrintable(text.mid(text.indexOf("Eye box (HOE following"), 200)));

    const Run mono = run(FOVEA_CLI_PATH, {"report", "", "--out", tmpDir() + "/r.pdf", "--eye", "left"});
    QCOMPARE(mono.code, 2);
    QVERIFY2(mono.err.contains("monocular scene"), qPrintable(mono.err));
  }

  // The retinal image's options from the command line (issue 29; the studio takes them from the
  // Foveated preview's Retina image controls): echoed in the manifest, named in the figure's
  // caption with the speckle contrast; out-of-range values are refused before the studio starts.
  void retinaImageOptionsFromTheCommandLine() {
    const QString html = tmpDir() + "/retina-options.html";
    const Run r =
        run(FOVEA_CLI_PATH, {"report", "", "--out", html, "--rays", "100", "--retina-speckle", "4", "--retina-grain",
                             "pupil", "--retina-seed", "7", "--retina-calibration", "per-laser", "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const nlohmann::json m = nlohmann::json::parse(r.out.toStdString());
    QVERIFY2(m["problems"].empty(), r.out.toUtf8().constData());
    QCOMPARE(
        m["retina_image"],
        nlohmann::json(
            {{"speckle_patterns", 4}, {"speckle_grain", "pupil"}, {"calibration", "per-laser"}, {"speckle_seed", 7}}));
    QFile f(html);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(f.readAll());
    const int at = text.indexOf("Speckle: 4 patterns per laser, pupil grain (seed 7), contrast ");
    QVERIFY2(at > 0, qPrintable(text.mid(text.indexOf("The retinal image at gaze"), 600)));
    QVERIFY(text.mid(at, 300).contains("each laser warped on its own (per-laser calibration), lateral colour 0.0"));
    for (const QStringList& bad : {QStringList{"--retina-speckle", "17"}, QStringList{"--retina-grain", "coarse"},
                                   QStringList{"--retina-calibration", "two"}, QStringList{"--retina-seed", "0"}}) {
      const Run b = run(FOVEA_CLI_PATH, QStringList{"report", "", "--out", tmpDir() + "/bad.html"} + bad);
      QVERIFY2(b.code == 2, qPrintable(bad.join(' ') + ": " + b.err));
    }
  }

  void argumentAndSceneErrors() {
    QCOMPARE(run(FOVEA_CLI_PATH, {"report", "", "--out", tmpDir() + "/r.pdf", "--tolerance-spec",
                                  QString(FOVEA_SOURCE_DIR) + "/resources/tolerance/prototype-tolerance.json"})
                 .code,
             2);  // without trials
    QCOMPARE(run(FOVEA_CLI_PATH, {"report", "", "--out", tmpDir() + "/r.txt"}).code, 2);
    QCOMPARE(run(FOVEA_CLI_PATH, {"report", "", "--out", tmpDir() + "/r.pdf", "--gaze-deg", "120"}).code, 2);
    QCOMPARE(run(FOVEA_CLI_PATH, {"report", "", "--out", tmpDir() + "/r.pdf", "--gaze-deg", "ten"}).code, 2);
    const QString bad = tmpDir() + "/broken.json";
    QFile b(bad);
    QVERIFY(b.open(QIODevice::WriteOnly));
    b.write("{\"format_version\": 1, \"eye\": ");
    b.close();
    const Run r = run(FOVEA_CLI_PATH, {"report", bad, "--out", tmpDir() + "/r.pdf"});
    QCOMPARE(r.code, 1);
    QVERIFY(!r.err.isEmpty());
  }
};

QTEST_MAIN(TestReport)  // the tolerance section renders its plots (Qt Charts needs a QApplication)

}  // namespace tst_report
#include "tst_report.moc"
