// `fovea-cli report` (driving `fovea-studio --report`): the PDF's page count and embedded
// images checked with poppler-utils (pdfinfo, pdfimages -list) against the manifest, the
// self-contained HTML's base64 images decoded, and the argument / scene errors' exit codes.
#include <QtTest>

#include <QImage>
#include <QProcess>
#include <QRegularExpression>
#include <QStandardPaths>

#include <nlohmann/json.hpp>

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
    // 4 standard 3-D views + 2 gaze views + 2 retina maps + FOV, travel, efficiency vs angle and
    // vs wavelength, resolution, Kogelnik vs RCWA.
    QCOMPARE(figures, 14);

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
    const Run r = run(FOVEA_CLI_PATH, {"report", "", "--out", html, "--gaze-deg", "5,2", "--rays", "300", "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const nlohmann::json m = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(m["pages"].is_null());
    QFile f(html);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(f.readAll());
    QVERIFY(text.startsWith("<!DOCTYPE html>"));
    static const QRegularExpression img("<img src='data:image/png;base64,([A-Za-z0-9+/=]+)'");
    int n = 0;
    for (auto it = img.globalMatch(text); it.hasNext();) {
      const QImage decoded = QImage::fromData(QByteArray::fromBase64(it.next().captured(1).toLatin1()), "PNG");
      QVERIFY(!decoded.isNull() && decoded.width() >= 300);
      ++n;
    }
    QCOMPARE(n, m["figures"].get<int>());
    QCOMPARE(n, 12);                          // 4 views + 1 gaze view + 1 retina map + 6 plots
    QVERIFY(!text.contains("src='figure-"));  // nothing outside the file
    QVERIFY(text.contains("Figure 1.") && text.contains("Key numbers") && text.contains("Scene summary"));
    QVERIFY(text.contains("Eye box"));
  }

  void argumentAndSceneErrors() {
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

QTEST_GUILESS_MAIN(TestReport)
#include "tst_report.moc"
