// fovea-cli devices / stage contracts: JSON keys, the --trace line format, exit codes 2
// (soft limits, nothing sent) and 3 (silent or missing device), degrees for rotation stages.
#include <QtTest>
#include "tests/test_paths.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_stage {

namespace {
using Run = fovea::testing::CliOutput;
Run cli(const QStringList& args) {
  return fovea::testing::runFoveaCli(args, 60000);
}
QString tmp(const char* name) {
  return QString::fromStdString((fovea::testing::testTmpDir("") / (std::string("cli_stage_") + name)).string());
}
std::vector<std::string> lines(const QString& path) {
  std::ifstream in(path.toStdString());
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}
bool hasLine(const std::vector<std::string>& ls, const std::string& prefix) {
  for (const auto& l : ls)
    if (l.rfind(prefix, 0) == 0) return true;
  return false;
}
}  // namespace

class TestCliStage : public QObject {
  Q_OBJECT
 private slots:
  void devicesJson() {
    const Run r = cli({"devices", "--json"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(j["devices"].is_array());
    int virtual_stages = 0, virtual_cameras = 0;
    std::string last_stage_model;
    for (const auto& d : j["devices"]) {
      for (const char* key : {"kind", "model", "serial"}) QVERIFY(d[key].is_string());
      QVERIFY(d["virtual"].is_boolean());
      if (d["virtual"].get<bool>() && d["kind"] == "stage-controller") {
        ++virtual_stages;
        last_stage_model = d["model"].get<std::string>();
      }
      if (d["virtual"].get<bool>() && d["kind"] == "camera") ++virtual_cameras;
    }
    QCOMPARE(virtual_stages, 5);  // one per stage binding of the prototype bench
    QCOMPARE(virtual_cameras, 1);
    QCOMPARE(last_stage_model, std::string("K10CR1"));
  }

  void devicesListsARecordedUsbController() {
    // A KDC101 described for umockdev (sysfs + descriptors): listed as hardware, not virtual.
    const QString runner = QStandardPaths::findExecutable("umockdev-run");
    if (runner.isEmpty()) QSKIP("umockdev-run is not installed (scripts/install-deps.sh)");
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    // umockdev works by LD_PRELOAD, which an ASan build must be told to accept.
    env.insert("ASAN_OPTIONS", env.value("ASAN_OPTIONS") + ":verify_asan_link_order=0");
    p.setProcessEnvironment(env);
    p.start(runner, {"-d", QString(FOVEA_SOURCE_DIR) + "/tests/devices/data/kdc101.umockdev", "--", FOVEA_CLI_PATH,
                     "devices", "--json"});
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitCode(), 0);
    const auto j = nlohmann::json::parse(p.readAllStandardOutput().toStdString());
    int hardware = 0;
    for (const auto& d : j["devices"])
      if (!d["virtual"].get<bool>() && d["kind"] == "stage-controller") {
        ++hardware;
        QCOMPARE(d["serial"].get<std::string>(), std::string("27000001"));
        QCOMPARE(d["model"].get<std::string>(), std::string("KDC101"));
      }
    QCOMPARE(hardware, 1);
  }

  void moveWithTrace() {
    const QString trace = tmp("move.trace");
    const Run r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "--json", "move-abs", "15"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["position_mm"].get<double>(), 15.0);
    QCOMPARE(j["device"]["virtual"].get<bool>(), true);
    QCOMPARE(j["device"]["serial"].get<std::string>(), std::string("27000001"));
    const auto ls = lines(trace);
    QVERIFY(ls.size() >= 8);
    // QRegularExpression rather than std::regex: GCC 12's <regex> trips -Wmaybe-uninitialized under ASan.
    const QRegularExpression format("^(TX|RX)( [0-9A-F]{2})+$");
    for (const auto& l : ls) QVERIFY2(format.match(QString::fromStdString(l)).hasMatch(), l.c_str());
    QCOMPARE(ls.front(), std::string("TX 05 00 00 00 50 01"));  // HW_REQ_INFO first
    // 15 mm x 34 304 = 514 560 = 0x0007DA00 -> LE 00 DA 07 00.
    const std::string move = "TX 53 04 06 00 D0 01 01 00 00 DA 07 00";
    const auto at = std::find(ls.begin(), ls.end(), move);
    QVERIFY2(at != ls.end(), "no MOT_MOVE_ABSOLUTE line");
    QVERIFY((at + 1)->rfind("RX 64 04 0E 00 81 50 01 00 00 DA 07 00", 0) == 0);  // MOVE_COMPLETED at 15 mm
  }

  void softLimitExit2SendsNoMove() {
    const QString trace = tmp("limit.trace");
    std::filesystem::remove(trace.toStdString());  // a refused command leaves it as it was: none
    Run r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "move-abs", "22"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("soft limits"), r.err.constData());
    QVERIFY(lines(trace).empty());
    // Relative: the position is read, but no move message leaves.
    r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "move-rel", "-9"});
    QCOMPARE(r.code, 2);
    const auto ls = lines(trace);
    QVERIFY(hasLine(ls, "TX 90 04"));
    QVERIFY(!hasLine(ls, "TX 48 04") && !hasLine(ls, "TX 53 04") && !hasLine(ls, "TX 6A 04"));
    // An explicit override widens the window: now the same move runs.
    r = cli({"stage", "--virtual", "MTS25-Z8", "--soft-limits", "0,25", "move-abs", "22"});
    QCOMPARE(r.code, 0);
  }

  void refusedBeforeAnyByte() {
    const QString trace = tmp("refused.trace");
    std::filesystem::remove(trace.toStdString());  // a refused command leaves it as it was: none
    // Reversed limits are refused, not swapped.
    Run r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "--soft-limits", "8,-8", "position"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--soft-limits 8,-8: expected MIN,MAX with MIN < MAX (mm)"), r.err.constData());
    // An absurd timeout is refused instead of printing a negative number of seconds.
    r = cli({"stage", "--virtual", "MTS25-Z8", "--timeout", "1e308", "position"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--timeout: expected seconds in (0, 3600], got 1e+308"), r.err.constData());
    // 1e12 deg does not fit the protocol's 32-bit counts, whatever the soft limits say.
    r = cli({"stage", "--virtual", "K10CR1", "--trace", trace, "--soft-limits", "-1e308,1e308", "move-abs", "1e12"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("beyond the protocol's signed 32-bit range; nothing was sent"), r.err.constData());
    QVERIFY(lines(trace).empty());
    r = cli({"stage", "--virtual", "K10CR1", "--trace", trace, "move-rel", "1e12"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("32-bit"), r.err.constData());
    QVERIFY(lines(trace).empty());
    // A soft-limit override is intersected with the stage's travel: 30 mm stays out of reach.
    r = cli({"stage", "--virtual", "MTS25-Z8", "--json", "--soft-limits", "-100,100", "move-abs", "30"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("outside the soft limits [0.0000, 25.0000]") ||
                 r.err.contains("outside the soft limits [0.0000 mm, 25.0000 mm]"),
             r.err.constData());
    r = cli({"stage", "--virtual", "MTS25-Z8", "--json", "--soft-limits", "-100,100", "position"});
    QCOMPARE(r.code, 0);
    const auto j = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(j["soft_limits_mm"][0].get<double>(), 0.0);
    QCOMPARE(j["soft_limits_mm"][1].get<double>(), 25.0);
    r = cli({"stage", "--virtual", "MTS25-Z8", "--soft-limits", "30,40", "position"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("no overlap with the travel [0, 25] mm of the MTS25-Z8"), r.err.constData());
  }

  void controllerErrorInWords() {
    const QString trace = tmp("reject.trace");
    const Run r =
        cli({"stage", "--virtual", "MTS25-Z8", "--virtual-fault", "reject", "--trace", trace, "move-abs", "14"});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("reported code 0x0001 (1) after MOT_MOVE_ABSOLUTE: virtual fault: motion command rejected"),
             r.err.constData());
    QVERIFY(hasLine(lines(trace), "RX 81 00 44 00 81 50 53 04 01 00"));  // HW_RICHRESPONSE
  }

  void infoShowsControllerSetUp() {
    const QString transcript = tmp("info.apt");
    const Run r = cli({"stage", "--virtual", "MTS25-Z8", "--json", "--transcript", transcript, "info"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto j = nlohmann::json::parse(r.out.toStdString());
    const auto& c = j["controller_setup"];
    QVERIFY(std::abs(c["velocity"]["max_mm_per_s"].get<double>() - 2.0) < 1e-5);
    QCOMPARE(c["jog"]["mode"].get<std::string>(), std::string("single-step"));
    QVERIFY(std::abs(c["jog"]["step_mm"].get<double>() - 0.1) < 1e-4);
    QCOMPARE(c["home"]["direction"].get<std::string>(), std::string("reverse"));
    QVERIFY(std::abs(c["home"]["velocity_mm_per_s"].get<double>() - 1.0) < 1e-5);
    QCOMPARE(c["limit_switches"]["cw_hard"].get<int>(), 2);
    QVERIFY(c["written"].is_array() && c["written"].empty());
    QCOMPARE(j["counts_per_mm"].get<double>(), 34304.0);
    QVERIFY(j["counts_source"].get<std::string>().find("protocol document") != std::string::npos);
    // The transcript: a header comment, then "SECONDS TX|RX HH ..." lines from 0.
    const auto ls = lines(transcript);
    QVERIFY(ls.size() > 10);
    QVERIFY(ls[0].rfind("#", 0) == 0);
    QVERIFY2(ls[1].rfind("0.000000 TX 05 00 00 00 50 01", 0) == 0, ls[1].c_str());
    QVERIFY(ls[2].find(" RX 06 00 54 00 81 50") != std::string::npos);
  }

  // The logs are written by the one output writer once the device was talked to: a refused move
  // leaves an existing transcript as it was, one file cannot be both logs, a device node is
  // refused (issue 28).
  void logsAreOutputsOfTheirOwn() {
    const QString transcript = tmp("kept.apt");
    { std::ofstream(transcript.toStdString()) << "# an earlier session\n0.000000 TX 05 00 00 00 50 01\n"; }
    Run r = cli({"stage", "--virtual", "MTS25-Z8", "--transcript", transcript, "move-abs", "22"});
    QCOMPARE(r.code, 2);
    QCOMPARE(lines(transcript).size(), std::size_t(2));
    QCOMPARE(lines(transcript)[0], std::string("# an earlier session"));
    r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", transcript, "--transcript", transcript, "position"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--trace and --transcript name the same file"), r.err.constData());
    QCOMPARE(lines(transcript).size(), std::size_t(2));
    r = cli({"stage", "--virtual", "MTS25-Z8", "--transcript", "/dev/full", "position"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--transcript: /dev/full: is a character device, not a regular file"), r.err.constData());
    r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", "", "position"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--trace: an empty path names no file"), r.err.constData());
  }

  // stage --replay TRANSCRIPT: a recorded session played as the device gives the same answer;
  // a host that sends something else is stopped at the transcript's line (exit 1).
  void replayARecordedSession() {
    const QString transcript = tmp("replay.apt");
    Run rec = cli({"stage", "--virtual", "MTS25-Z8", "--json", "--transcript", transcript, "move-abs", "15"});
    QVERIFY2(rec.code == 0, rec.err.constData());
    const auto live = nlohmann::json::parse(rec.out.toStdString());
    Run r = cli({"stage", "--virtual", "MTS25-Z8", "--json", "--replay", transcript, "move-abs", "15"});
    QVERIFY2(r.code == 0, r.err.constData());
    const auto replayed = nlohmann::json::parse(r.out.toStdString());
    QCOMPARE(replayed["position_mm"].get<double>(), live["position_mm"].get<double>());
    QCOMPARE(replayed["position_mm"].get<double>(), 15.0);
    QCOMPARE(replayed["replay"]["file"].get<std::string>(), transcript.toStdString());
    QCOMPARE(replayed["replay"]["entries_not_played"].get<int>(), 0);
    // Another target: the host's MOVE_ABSOLUTE differs from the recorded one.
    r = cli({"stage", "--virtual", "MTS25-Z8", "--json", "--replay", transcript, "move-abs", "16"});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains(transcript.toUtf8() + ":") && r.err.contains("the transcript expects TX"),
             r.err.constData());
    // A transcript that is no file, or malformed, is named.
    r = cli({"stage", "--virtual", "MTS25-Z8", "--replay", "/dev/zero", "position"});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("--replay: cannot read the transcript '/dev/zero': is a character device"),
             r.err.constData());
    const QString bad = tmp("bad.apt");
    { std::ofstream(bad.toStdString()) << "0 TX 05 00\n0 XX 01\n"; }
    r = cli({"stage", "--virtual", "MTS25-Z8", "--replay", bad, "position"});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains(bad.toUtf8() + ":2: expected TX, RX or UNPLUG"), r.err.constData());
  }

  void silentOrMissingDeviceExit3() {
    Run r = cli({"stage", "--virtual", "MTS25-Z8", "--virtual-fault", "mute", "--timeout", "0.5", "position"});
    QCOMPARE(r.code, 3);
    QVERIFY2(r.err.contains("did not answer"), r.err.constData());
    r = cli({"stage", "--serial", "27999999", "position"});
    QCOMPARE(r.code, 3);
    QVERIFY2(r.err.contains("27999999"), r.err.constData());
  }

  void rotationStageInDegrees() {
    Run r = cli({"stage", "--virtual", "K10CR1", "--json", "move-abs", "12.5"});
    QVERIFY2(r.code == 0, r.err.constData());
    auto j = nlohmann::json::parse(r.out.toStdString());
    QVERIFY(std::abs(j["position_deg"].get<double>() - 12.5) < 1e-5);
    QVERIFY(!j.contains("position_mm"));
    QCOMPARE(j["unit"].get<std::string>(), std::string("deg"));
    r = cli({"stage", "--virtual", "K10CR1", "move-abs", "30"});  // scene limits +-25 deg
    QCOMPARE(r.code, 2);
  }

  void jogStopHomeEnable() {
    const QString trace = tmp("ops.trace");
    Run r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "--json", "jog", "reverse"});
    QVERIFY2(r.code == 0, r.err.constData());
    QVERIFY(hasLine(lines(trace), "TX 6A 04 01 02 50 01"));
    QVERIFY(std::abs(nlohmann::json::parse(r.out.toStdString())["position_mm"].get<double>() - 12.4) <
            1e-4);  // 12.5 - 0.1 step
    r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "stop", "--immediate"});
    QCOMPARE(r.code, 0);
    QVERIFY(hasLine(lines(trace), "TX 65 04 01 01 50 01"));
    QVERIFY(hasLine(lines(trace), "RX 66 04 0E 00 81 50"));  // MOVE_STOPPED
    r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "--json", "home"});
    QCOMPARE(r.code, 0);
    QVERIFY(hasLine(lines(trace), "TX 43 04 01 00 50 01"));
    QVERIFY(hasLine(lines(trace), "RX 44 04 01 00 01 50"));  // MOVE_HOMED
    QCOMPARE(nlohmann::json::parse(r.out.toStdString())["position_mm"].get<double>(), 0.0);
    r = cli({"stage", "--virtual", "MTS25-Z8", "--trace", trace, "--json", "disable"});
    QCOMPARE(r.code, 0);
    QVERIFY(hasLine(lines(trace), "TX 10 02 01 02 50 01"));
    QCOMPARE(nlohmann::json::parse(r.out.toStdString())["enabled"].get<bool>(), false);
    r = cli({"stage", "--virtual", "MTS25-Z8", "--json", "info"});
    QCOMPARE(r.code, 0);
    QCOMPARE(nlohmann::json::parse(r.out.toStdString())["hardware"]["model"].get<std::string>(), std::string("KDC101"));
  }

  void badArguments() {
    QCOMPARE(cli({"stage", "--virtual", "MTS25-Z8", "move-abs", "nan"}).code, 2);
    QCOMPARE(cli({"stage", "--virtual", "MTS25-Z8", "jog", "sideways"}).code, 2);
    QCOMPARE(cli({"stage", "--virtual", "NOPE", "position"}).code, 2);
    QCOMPARE(cli({"stage", "position"}).code, 2);
    QCOMPARE(cli({"stage", "--virtual", "MTS25-Z8", "--serial", "27000001", "position"}).code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCliStage)

}  // namespace tst_cli_stage
#include "tst_cli_stage.moc"
