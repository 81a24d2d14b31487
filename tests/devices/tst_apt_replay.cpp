// Replay tests: transcripts (tests/devices/data/replay/*.apt, bytes laid out from the APT
// protocol document by make_transcripts.py) played through ReplayTransport against the
// real Stage, and the host side of one played against the emulator. Each transcript is a
// behaviour of real controllers: completion with the moving bits set, an error response, the
// header-only move forms, a limit switch hit mid-move, an unplug mid-move.
#include <QtTest>
#include "tests/test_paths.h"

#include "devices/apt/apt_decoder.h"
#include "devices/replay/replay_transport.h"
#include "devices/stage/stage.h"
#include "devices/virtual/virtual_transport.h"

namespace tst_apt_replay {

using namespace fovea::devices;
namespace apt = fovea::apt;

namespace {
std::string transcriptPath(const char* name) {
  return std::string(FOVEA_SOURCE_DIR) + "/tests/devices/data/replay/" + name;
}

struct Replay {
  ReplayTransport* link = nullptr;  // owned by the stage
  std::unique_ptr<Stage> stage;
  Replay(const char* file, const char* controller, const char* stage_model) {
    DeviceInfo info;
    info.model = controller;
    info.serial = std::string(controller) == "K10CR1" ? "55000001" : "27000001";
    auto t = std::make_unique<ReplayTransport>(readTranscriptFile(transcriptPath(file)), info, file);
    link = t.get();
    StageConfig c = defaultStageConfig(*apt::findController(controller), *apt::findStage(stage_model));
    stage = std::make_unique<Stage>(std::move(t), c);
  }
};

template <class F>
std::pair<DeviceError::Kind, std::string> deviceError(F f) {
  try {
    f();
  } catch (const DeviceError& e) {
    return {e.kind(), e.what()};
  }
  return {DeviceError::Kind::Usage, "no error"};
}
}  // namespace

class TestAptReplay : public QObject {
  Q_OBJECT
 private slots:
  void transcriptFormat() {
    const auto e = parseTranscript("# comment\n\n0.5 TX 05 00 00 00 50 01\n0.75 RX 12 02 01 01 01 50\r\n2 UNPLUG\n");
    QCOMPARE(e.size(), std::size_t{3});
    QCOMPARE(e[0].kind, TranscriptEntry::Kind::Tx);
    QCOMPARE(e[0].bytes, (std::vector<std::uint8_t>{0x05, 0, 0, 0, 0x50, 0x01}));
    QCOMPARE(e[1].t_s, 0.75);
    QCOMPARE(e[1].line, 4);
    QCOMPARE(e[2].kind, TranscriptEntry::Kind::Unplug);
    const std::uint8_t raw[] = {0x23, 0x02, 0x00, 0x00, 0x50, 0x01};
    QCOMPARE(transcriptLine(1.25, true, raw), std::string("1.250000 TX 23 02 00 00 50 01"));
    // Malformed lines are named with their line number.
    const std::pair<const char*, const char*> bad[] = {
        {"1 TX 05 00\n0.5 RX 06 00\n", "t:2: time 0.5 s runs backwards"},
        {"0 TX 5G\n", "t:1: expected hex byte pairs"},
        {"0 XX 05\n", "t:1: expected TX, RX or UNPLUG"},
        {"abc TX 05\n", "t:1: expected a time in seconds"},
        {"0 RX\n", "t:1: RX without bytes"},
        {"0 UNPLUG 01\n", "t:1: UNPLUG takes no bytes"},
    };
    for (const auto& [text, message] : bad) {
      QString what;
      try {
        parseTranscript(text, "t");
      } catch (const std::invalid_argument& ex) {
        what = ex.what();
      }
      QVERIFY2(what.startsWith(message), qPrintable(what));
    }
  }

  void completionWithMovingBitsDoesNotLie() {
    // The K10CR1's MOVE_COMPLETED says "moving, not homed"; the poll after it says "homed,
    // at rest". The state must follow the poll, and the second move must be accepted.
    Replay r("k10cr1-completion-moving-bits.apt", "K10CR1", "K10CR1");
    r.stage->connect();
    r.stage->moveAbsolute(10.0);
    AxisState s = r.stage->state();
    QVERIFY(s.homed && !s.moving && s.known);
    QVERIFY(std::abs(s.position - 10.0) < 1e-5);
    r.stage->moveAbsolute(20.0);
    s = r.stage->state();
    QVERIFY(s.homed && !s.moving);
    QVERIFY(std::abs(s.position - 20.0) < 1e-5);
    QCOMPARE(r.link->remaining(), std::size_t{0});
    // Connect read the controller set-up: velocity 10 deg/s, jog 1 deg, home 5 deg/s.
    const auto& p = r.stage->controllerParameters();
    QVERIFY(std::abs(p.velocity.max_velocity - 10.0) < 1e-6);
    QVERIFY(p.jog && std::abs(p.jog->step - 1.0) < 1e-5);
    QVERIFY(p.home && std::abs(p.home_velocity - 5.0) < 1e-6);
    QVERIFY(p.limit_switches && p.limit_switches->cw_hard == 2);
  }

  void errorResponseEndsTheWaitInWords() {
    Replay r("kdc101-error-response.apt", "KDC101", "MTS25-Z8");
    r.stage->connect();
    const double t0 = r.link->now();
    const auto [kind, what] = deviceError([&] { r.stage->moveAbsolute(5.0); });
    QCOMPARE(kind, DeviceError::Kind::Controller);
    for (const char* part : {"code 0x0011 (17)", "after MOT_MOVE_ABSOLUTE", "Motor drive fault: check the stage cable"})
      QVERIFY2(what.find(part) != std::string::npos, what.c_str());
    // Within the reply (4 ms), not after the move's timeout (> 3 s).
    QVERIFY2(r.link->now() - t0 < 0.1, std::to_string(r.link->now() - t0).c_str());
    QVERIFY(r.stage->lastControllerError().find("0x0011") != std::string::npos);
    QCOMPARE(r.link->remaining(), std::size_t{0});
  }

  void limitSwitchHitMidMove() {
    Replay r("kdc101-limit-switch-hit.apt", "KDC101", "MTS25-Z8");
    r.stage->connect();
    const auto [kind, what] = deviceError([&] { r.stage->moveAbsolute(20.0); });
    QCOMPARE(kind, DeviceError::Kind::Protocol);
    QVERIFY2(what.find("ended early at 12.3000 mm (limit switch)") != std::string::npos, what.c_str());
    QVERIFY(r.stage->state().forward_limit && !r.stage->state().moving);
    QCOMPARE(r.link->remaining(), std::size_t{0});
  }

  void unplugMidMove() {
    Replay r("kdc101-unplug-mid-move.apt", "KDC101", "MTS25-Z8");
    r.stage->connect();
    const auto [kind, what] = deviceError([&] { r.stage->moveAbsolute(20.0); });
    QCOMPARE(kind, DeviceError::Kind::Disconnected);
    QVERIFY2(what.find("position unknown until reconnect") != std::string::npos, what.c_str());
    QVERIFY(!r.stage->state().known);
    QVERIFY(!r.stage->connected());
    QVERIFY(std::abs(r.link->now() - 1.0 - 0.014) < 0.06);  // the unplug's time, in 50 ms read slices
    QCOMPARE(r.link->remaining(), std::size_t{0});
  }

  void replayRefusesDifferentHostBytes() {
    // The host moving to 6 mm where the transcript recorded 5 mm: named, with both byte strings.
    Replay r("kdc101-error-response.apt", "KDC101", "MTS25-Z8");
    r.stage->connect();
    const auto [kind, what] = deviceError([&] { r.stage->moveAbsolute(6.0); });
    QCOMPARE(kind, DeviceError::Kind::Protocol);
    QVERIFY2(what.find("kdc101-error-response.apt:") != std::string::npos &&
                 what.find("the transcript expects TX 53 04 06 00 D0 01 01 00 00 9E 02 00") != std::string::npos,
             what.c_str());
  }

  void shortFormsAgainstTheEmulator() {
    // Play the host's side into the emulator; its replies must be the transcript's RX bytes.
    auto clock = std::make_shared<SimulatedClock>();
    auto emulator = makeVirtualController("MTS25-Z8", "", clock);
    const auto entries = readTranscriptFile(transcriptPath("kdc101-short-form.apt"));
    int rx_checked = 0;
    for (const auto& e : entries) {
      if (e.kind == TranscriptEntry::Kind::Tx) {
        emulator->receive(e.bytes);
        // The decoder takes the header-only form as a whole message.
        apt::StreamDecoder d;
        d.feed(e.bytes);
        const auto m = d.next();
        QVERIFY(m.has_value());
        QCOMPARE(apt::encode(*m), e.bytes);
        continue;
      }
      QCOMPARE(e.kind, TranscriptEntry::Kind::Rx);
      std::vector<std::uint8_t> out;
      for (int guard = 0; out.empty() && guard < 100; ++guard) {
        clock->waitUntil(std::min(emulator->nextEventTime(), clock->now() + 1.0));
        out = emulator->takeOutput();
      }
      QCOMPARE(apt::toHex(out), apt::toHex(e.bytes));
      ++rx_checked;
    }
    QCOMPARE(rx_checked, 2);
    QVERIFY(std::abs(emulator->position() - 6.0) < 1e-9);
  }
};

QTEST_GUILESS_MAIN(TestAptReplay)

}  // namespace tst_apt_replay
#include "tst_apt_replay.moc"
