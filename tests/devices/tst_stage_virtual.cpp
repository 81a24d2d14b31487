// Every Stage operation against the APT emulator through the real Transport interface, on
// a simulated clock (instant, deterministic): timings checked against the trapezoid closed
// form, soft limits that send nothing, timeouts, unplug during a move, e-stop.
#include <QtTest>

#include <cmath>

#include "devices/stage/stage.h"
#include "devices/stage/stage_binding.h"
#include "devices/virtual/virtual_transport.h"

namespace tst_stage_virtual {

using namespace fovea::devices;
namespace apt = fovea::apt;

namespace {
struct Rig {
  std::shared_ptr<SimulatedClock> clock = std::make_shared<SimulatedClock>();
  std::shared_ptr<VirtualAptController> controller;
  VirtualTransport* link = nullptr;  // owned by the stage
  std::shared_ptr<AptMemoryLog> trace = std::make_shared<AptMemoryLog>();
  std::unique_ptr<Stage> stage;

  explicit Rig(const std::string& model = "MTS25-Z8", std::function<void(VirtualControllerConfig&)> tweak = {},
               std::optional<std::pair<double, double>> soft = std::nullopt) {
    auto base = makeVirtualController(model, "", clock);
    VirtualControllerConfig cfg = base->config();
    if (tweak) tweak(cfg);
    controller = std::make_shared<VirtualAptController>(cfg, clock);
    auto t = std::make_unique<VirtualTransport>(controller, clock);
    link = t.get();
    StageConfig sc = defaultStageConfig(cfg.controller, cfg.stage);
    if (soft) std::tie(sc.soft_min, sc.soft_max) = *soft;
    stage = std::make_unique<Stage>(std::move(t), sc, trace);
  }
  bool traceHas(const std::string& prefix) const {
    for (const auto& l : trace->lines())
      if (l.rfind(prefix, 0) == 0) return true;
    return false;
  }
};

// Trapezoid time with the quantised APT velocity parameters the controller really uses.
double trapezoidTime(double d, double v, double a) {
  return d >= v * v / a ? v / a + d / v : 2 * std::sqrt(d / a);
}
}  // namespace

class TestStageVirtual : public QObject {
  Q_OBJECT
 private slots:
  void connectReadsInfoAndState() {
    Rig r;
    r.stage->connect();
    QCOMPARE(r.stage->hardwareInfo().model, std::string("KDC101"));
    QCOMPARE(r.stage->hardwareInfo().serial, std::uint32_t{27000001});
    const AxisState s = r.stage->state();
    QVERIFY(s.known && s.homed && s.enabled && !s.moving);
    QCOMPARE(s.position, 0.0);
    QVERIFY(s.reverse_limit);  // at the home switch
    // The trace starts with the exact request bytes.
    QCOMPARE(r.trace->lines().front(), std::string("TX 05 00 00 00 50 01"));
    QVERIFY(r.trace->lines()[1].rfind("RX 06 00 54 00 81 50", 0) == 0);
    r.stage->identify();
    QCOMPARE(r.controller->identifyCount(), 1);
  }

  void homingTakesTheTrapezoidTime() {
    Rig r("MTS25-Z8", [](VirtualControllerConfig& c) {
      c.homed = false;
      c.position = 10.0;
    });
    r.stage->connect();
    QVERIFY(!r.stage->state().homed);
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->moveAbsolute(5.0));  // not homed
    QVERIFY(!r.traceHas("TX 53 04"));
    const double t0 = r.clock->now();
    r.stage->home();
    const auto& u = r.stage->units();
    const double a = u.aptToAcceleration(r.controller->velParams().acceleration);
    // The HOMEPARAMS velocity: the MTS25-Z8's 1 mm/s homing speed, quantised to APT units.
    const double hv = u.aptToVelocity(r.controller->homeParams().velocity);
    QVERIFY(std::abs(hv - 1.0) < 1e-5);
    const double expected = trapezoidTime(10.0, hv, a);
    QVERIFY2(std::abs(r.clock->now() - t0 - expected) < 1e-6, qPrintable(QString::number(r.clock->now() - t0)));
    QVERIFY(r.stage->state().homed);
    QCOMPARE(r.stage->state().position, 0.0);
  }

  void movesAndVelocityParameters() {
    Rig r;
    r.stage->connect();
    const VelocitySettings v = r.stage->velocity();
    QVERIFY(std::abs(v.max_velocity - 2.0) < 1e-5);  // default 2 mm/s quantised to APT units
    QVERIFY(std::abs(v.acceleration - 1.5) < 2e-3);
    double t0 = r.clock->now();
    r.stage->moveAbsolute(5.0);
    // 5 mm at 2 mm/s, 1.5 mm/s^2: v/a + d/v = 1.333 + 2.5 = 3.833 s.
    QVERIFY(std::abs(r.clock->now() - t0 - trapezoidTime(5.0, v.max_velocity, v.acceleration)) < 1e-6);
    QVERIFY(std::abs(r.clock->now() - t0 - 3.8333) < 2e-3);
    QVERIFY(std::abs(r.stage->state().position - 5.0) < 1.0 / 34304);
    r.stage->moveRelative(-1.5);
    QVERIFY(std::abs(r.stage->state().position - 3.5) < 1.0 / 34304);
    // Slower: 0.5 mm/s, 1 mm/s^2; a 0.1 mm move is a triangle: 2 sqrt(0.1/1) = 0.632 s.
    r.stage->setVelocity({0.5, 1.0});
    const VelocitySettings slow = r.stage->velocity();
    QVERIFY(std::abs(slow.max_velocity - 0.5) < 1e-5);
    t0 = r.clock->now();
    r.stage->moveRelative(0.1);
    const double d = r.stage->units().countsToPosition(r.stage->units().positionToCounts(0.1));  // 3430 counts
    QVERIFY(std::abs(r.clock->now() - t0 - 2 * std::sqrt(d / slow.acceleration)) < 1e-6);
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->setVelocity({50.0, 1.0}));  // beyond the Z8's 2.4 mm/s
    // Beyond the stage's travel: refused before any byte, whatever the soft limits say.
    Rig wide("MTS25-Z8", {}, std::make_pair(-5.0, 30.0));
    wide.stage->connect();
    try {
      wide.stage->moveAbsolute(28.0);
      QFAIL("a move beyond the travel was sent");
    } catch (const DeviceError& e) {
      QCOMPARE(e.kind(), DeviceError::Kind::SoftLimit);
      QVERIFY2(
          std::string(e.what()).find("outside the travel [0.0000 mm, 25.0000 mm] of the MTS25-Z8") != std::string::npos,
          e.what());
    }
    QVERIFY(!wide.traceHas("TX 53 04"));
    // A limit switch that closes early (here at 20 mm) ends the move with MOVE_STOPPED: an error.
    auto early_switch = std::make_shared<VirtualAptController>(
        [&] {
          VirtualControllerConfig c = wide.controller->config();
          c.stage.travel_max = 20.0;  // the emulated switch; the host keeps the model's 25 mm
          return c;
        }(),
        wide.clock);
    Stage short_travel(std::make_unique<VirtualTransport>(early_switch, wide.clock),
                       defaultStageConfig(*apt::findController("KDC101"), *apt::findStage("MTS25-Z8")));
    short_travel.connect();
    try {
      short_travel.moveAbsolute(22.0);
      QFAIL("a move through the limit switch reported success");
    } catch (const DeviceError& e) {
      QVERIFY2(std::string(e.what()).find("limit switch") != std::string::npos, e.what());
    }
    QCOMPARE(short_travel.state().position, 20.0);
    QVERIFY(short_travel.state().forward_limit);
  }

  void softLimitsSendNothing() {
    Rig r("MTS25-Z8", {}, std::make_pair(4.5, 20.5));
    r.stage->connect();
    r.stage->moveAbsolute(10.0);
    const auto before = r.trace->lines().size();
    try {
      r.stage->moveAbsolute(21.0);
      QFAIL("move outside the soft limits was accepted");
    } catch (const DeviceError& e) {
      QVERIFY(e.kind() == DeviceError::Kind::SoftLimit);
      QVERIFY(std::string(e.what()).find("20.5") != std::string::npos);
    }
    QCOMPARE(r.trace->lines().size(), before);  // not a single byte
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->moveAbsolute(std::nan("")));
    QCOMPARE(r.trace->lines().size(), before);
    // Relative: the position is polled (a status request), but no move message goes out.
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->moveRelative(-6.0));
    for (std::size_t i = before; i < r.trace->lines().size(); ++i)
      QVERIFY(r.trace->lines()[i].rfind("TX 48 04", 0) != 0 && r.trace->lines()[i].rfind("TX 53 04", 0) != 0);
    QVERIFY(std::abs(r.controller->position() - 10.0) < 1e-9);
    // Scene binding: element limits -8..8 with home offset -12.5 -> stage 4.5 .. 20.5.
    fovea::StageBinding b;
    b.element = "hoe";
    b.axis = "x";
    b.controller = "KDC101";
    b.stage_model = "MTS25-Z8";
    b.soft_limits = {-8.0, 8.0};
    b.home_offset = -12.5;
    const StageConfig c = stageConfigForBinding(b);
    QCOMPARE(c.soft_min, 4.5);
    QCOMPARE(c.soft_max, 20.5);
    QCOMPARE(elementToStage(b, 0.0), 12.5);
    b.soft_limits = {-30.0, 30.0};  // clipped to the 0..25 mm travel
    QCOMPARE(stageConfigForBinding(b).soft_max, 25.0);
    b.stage_model = "XYZ";
    QVERIFY_THROWS_EXCEPTION(DeviceError, stageConfigForBinding(b));
  }

  void jogsUseJogParameters() {
    Rig r;
    r.stage->connect();
    r.stage->moveAbsolute(5.0);
    r.stage->setJogSettings({false, 0.25, 1.0, 1.0, false});
    const JogSettings j = r.stage->jogSettings();
    QVERIFY(!j.continuous);
    QVERIFY(std::abs(j.step - 0.25) < 1e-4);
    const double t0 = r.clock->now();
    r.stage->jog(apt::JogDirection::Forward);
    QVERIFY(std::abs(r.stage->state().position - 5.25) < 1e-4);
    QVERIFY(std::abs(r.clock->now() - t0 - trapezoidTime(0.25, j.max_velocity, j.acceleration)) < 1e-6);
    r.stage->jog(apt::JogDirection::Reverse);
    r.stage->jog(apt::JogDirection::Reverse);
    QVERIFY(std::abs(r.stage->state().position - 4.75) < 1e-4);
    QVERIFY(r.traceHas("TX 6A 04 01 01 50 01"));
    QVERIFY(r.traceHas("TX 6A 04 01 02 50 01"));
    // A jog step that would leave the soft limits is refused before sending.
    Rig edge("MTS25-Z8", {}, std::make_pair(0.0, 5.1));
    edge.stage->connect();
    edge.stage->moveAbsolute(5.0);
    edge.stage->setJogSettings({false, 0.25, 1.0, 1.0, false});
    QVERIFY_THROWS_EXCEPTION(DeviceError, edge.stage->jog(apt::JogDirection::Forward));
    QVERIFY(!edge.traceHas("TX 6A 04"));
    // Continuous jog mode cannot honour soft limits: refused.
    edge.stage->setJogSettings({true, 0.25, 1.0, 1.0, false});
    QVERIFY_THROWS_EXCEPTION(DeviceError, edge.stage->jog(apt::JogDirection::Reverse));
    QVERIFY(!edge.traceHas("TX 6A 04"));
  }

  void stopsProfiledAndImmediate() {
    Rig r;
    r.stage->connect();
    r.stage->startMoveAbsolute(20.0);
    const VelocitySettings v = r.stage->velocity();
    // After 2 s: accelerated 1.333 s (1.333 mm), cruised 0.667 s at 2 mm/s (1.333 mm).
    r.clock->advance(2.0);
    r.stage->stop(false);
    // Profiled stop from 2 mm/s at 1.5 mm/s^2 adds v^2/2a = 1.333 mm -> 4.0 mm.
    const double t_acc = v.max_velocity / v.acceleration;
    const double x_stop = 0.5 * v.acceleration * t_acc * t_acc + v.max_velocity * (2.0 - t_acc) +
                          v.max_velocity * v.max_velocity / (2 * v.acceleration);
    QVERIFY2(std::abs(r.stage->state().position - x_stop) < 1e-4,
             qPrintable(QString::number(r.stage->state().position)));
    QVERIFY(std::abs(x_stop - 4.0) < 2e-3);
    QVERIFY(!r.stage->state().moving);
    // Immediate: the axis stays where it was when the message arrived.
    r.stage->startMoveAbsolute(10.0);
    r.clock->advance(1.0);
    r.controller->advanceTo(r.clock->now());
    const double here = r.controller->position();
    r.stage->stop(true);
    QVERIFY(std::abs(r.stage->state().position - here) < 1.0 / 34304);
    QVERIFY(r.traceHas("TX 65 04 01 02 50 01"));
    QVERIFY(r.traceHas("TX 65 04 01 01 50 01"));
  }

  void enableDisable() {
    Rig r;
    r.stage->connect();
    r.stage->setEnabled(false);
    QVERIFY(!r.stage->state().enabled);
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->moveAbsolute(3.0));
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->home());
    QVERIFY(!r.traceHas("TX 53 04"));
    QVERIFY(!r.traceHas("TX 43 04"));
    r.stage->setEnabled(true);
    r.stage->poll();
    r.stage->moveAbsolute(3.0);
    QVERIFY(std::abs(r.stage->state().position - 3.0) < 1e-4);
  }

  void silentDeviceTimesOut() {
    Rig r;
    r.controller->setMute(true);
    try {
      r.stage->connect();
      QFAIL("a mute controller connected");
    } catch (const DeviceError& e) {
      QVERIFY(e.kind() == DeviceError::Kind::Timeout);
      QVERIFY2(std::string(e.what()).find("did not answer HW_REQ_INFO") != std::string::npos, e.what());
    }
    QVERIFY(std::abs(r.clock->now() - 2.0) < 1e-6);  // the 2 s reply timeout, on the simulated clock
  }

  void unplugDuringMoveLosesOnlyThatAxis() {
    Rig a, b;
    a.stage->connect();
    b.stage->connect();
    a.stage->moveAbsolute(2.0);
    a.stage->startMoveAbsolute(12.0);
    a.clock->advance(1.0);
    a.link->simulateUnplug();
    try {
      a.stage->waitForMotion(30.0);
      QFAIL("wait survived an unplug");
    } catch (const DeviceError& e) {
      QVERIFY(e.kind() == DeviceError::Kind::Disconnected);
      QVERIFY2(std::string(e.what()).find("position unknown") != std::string::npos, e.what());
    }
    QVERIFY(!a.stage->state().known);
    QVERIFY(!a.stage->connected());
    QVERIFY_THROWS_EXCEPTION(DeviceError, a.stage->moveAbsolute(3.0));
    // The other axis is untouched.
    b.stage->moveAbsolute(7.0);
    QVERIFY(std::abs(b.stage->state().position - 7.0) < 1e-4);
    // The cube kept running on its own supply; after replug the stage re-reads everything.
    a.clock->advance(20.0);
    a.link->replug();
    a.stage->reconnect();
    QVERIFY(a.stage->state().known);
    QVERIFY(std::abs(a.stage->state().position - 12.0) < 1e-4);
    QCOMPARE(a.stage->config().soft_max, 25.0);  // configuration kept
    a.stage->moveAbsolute(1.0);
    QVERIFY(std::abs(a.stage->state().position - 1.0) < 1e-4);
  }

  void emergencyStopStopsEveryAxis() {
    Rig a, b, c;
    for (Rig* r : {&a, &b, &c}) r->stage->connect();
    a.stage->startMoveAbsolute(20.0);
    b.stage->startMoveAbsolute(15.0);
    a.clock->advance(1.0);
    b.clock->advance(1.0);
    c.link->simulateUnplug();
    const auto problems = emergencyStop({a.stage.get(), b.stage.get(), c.stage.get()});
    QCOMPARE(problems.size(), std::size_t{1});  // only the unplugged axis
    QVERIFY(!a.controller->moving() && !b.controller->moving());
    QVERIFY(a.controller->position() < 1.0 && b.controller->position() < 1.0);  // stopped at once
    QVERIFY(a.traceHas("TX 65 04 01 01 50 01"));
  }

  void rotationStageInDegrees() {
    Rig r("K10CR1");
    r.stage->connect();
    QCOMPARE(r.stage->hardwareInfo().model, std::string("K10CR1"));
    r.stage->moveAbsolute(90.0);
    QVERIFY(std::abs(r.stage->state().position - 90.0) < 1e-5);
    // 90 deg = 12 288 000 = 0x00BB8000 counts -> LE 00 80 BB 00.
    QVERIFY(r.traceHas("TX 53 04 06 00 D0 01 01 00 00 80 BB 00"));
    // Stepper status: MOT_REQ_STATUSUPDATE 0x0480 -> GET 0x0481.
    QVERIFY(r.traceHas("TX 80 04 01 00 50 01"));
    QVERIFY(r.traceHas("RX 81 04 0E 00 81 50"));
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->moveAbsolute(200.0));  // default soft limits +-180 deg
  }

  void statusUpdateStreamAndKeepAlive() {
    auto clock = std::make_shared<SimulatedClock>();
    auto ctl = makeVirtualController("KDC101", "", clock);
    VirtualTransport link(ctl, clock);
    link.open();
    link.write(apt::encode(apt::startUpdateMsgs(0x50)));
    apt::StreamDecoder d;
    int updates = 0;
    while (clock->now() < 1.0 - 1e-9) {
      d.feed(link.read(std::chrono::milliseconds(1000)));
      while (auto m = d.next()) updates += m->id == apt::id::kMotGetDcStatusUpdate;
    }
    QCOMPARE(updates, 10);  // 10 Hz
    // Without MOT_ACK_DCSTATUSUPDATE the stream stops after 50 updates; with it, it goes on.
    for (int i = 0; i < 100; ++i) {
      d.feed(link.read(std::chrono::milliseconds(100)));
      while (auto m = d.next()) updates += m->id == apt::id::kMotGetDcStatusUpdate;
    }
    QCOMPARE(updates, 50);
    link.write(apt::encode(apt::startUpdateMsgs(0x50)));
    for (int i = 0; i < 100; ++i) {
      link.write(apt::encode(apt::ackDcStatusUpdate(0x50)));
      d.feed(link.read(std::chrono::milliseconds(100)));
      while (auto m = d.next()) updates += m->id == apt::id::kMotGetDcStatusUpdate;
    }
    QVERIFY(updates >= 149);
    link.write(apt::encode(apt::stopUpdateMsgs(0x50)));
    d.feed(link.read(std::chrono::milliseconds(1000)));
    QVERIFY(!d.next().has_value());
  }

  void completionStateComesFromThePoll() {
    // An emulator whose MOVE_COMPLETED says 0x80000030 (moving, not homed), like a K10CR1.
    Rig r("K10CR1", [](VirtualControllerConfig& c) { c.completion_reports_moving = true; });
    r.stage->connect();
    r.stage->moveAbsolute(10.0);
    QVERIFY(r.stage->state().homed && !r.stage->state().moving);
    r.stage->moveAbsolute(-5.0);  // accepted: not "not homed"
    QVERIFY(std::abs(r.stage->state().position + 5.0) < 1e-5);
    // Every completion is followed by a status poll (80 04 for a stepper).
    const auto lines = r.trace->lines();
    for (std::size_t i = 0; i + 1 < lines.size(); ++i)
      if (lines[i].rfind("RX 64 04", 0) == 0) QVERIFY(lines[i + 1].rfind("TX 80 04 01 00 50 01", 0) == 0);
  }

  void stepperCompletionHasZeroVelocityWord() {
    Rig r("K10CR1");
    r.stage->connect();
    r.stage->moveAbsolute(3.0);
    for (const auto& l : r.trace->lines()) {
      if (l.rfind("RX 64 04 0E 00 81 50", 0) != 0) continue;
      // Header (18 chars) + chan (6) + position (12): the velocity word follows.
      QCOMPARE(l.substr(3 + 18 + 6 + 12, 5), std::string("00 00"));
      QVERIFY(l.substr(3 + 18 + 6, 11) != "00 00 00 00");  // while the position is not zero
      return;
    }
    QFAIL("no MOVE_COMPLETED in the trace");
  }

  void controllerSetUpOnConnect() {
    Rig r;
    StageConfig c = r.stage->config();
    c.setup.max_velocity = 1.2;
    c.setup.acceleration = 2.0;
    c.setup.jog_step = 0.25;
    c.setup.home_velocity = 0.8;
    c.setup.limit_switch_mode = 3;
    auto t = std::make_unique<VirtualTransport>(r.controller, r.clock);
    Stage s(std::move(t), c, r.trace);
    s.connect();
    const auto& u = s.units();
    QVERIFY(std::abs(u.aptToVelocity(r.controller->velParams().max_velocity) - 1.2) < 1e-5);
    QVERIFY(std::abs(u.countsToPosition(r.controller->jogParams().step_size) - 0.25) < 1e-4);
    QVERIFY(std::abs(u.aptToVelocity(r.controller->homeParams().velocity) - 0.8) < 1e-5);
    QCOMPARE(r.controller->limSwitchParams().cw_hard, std::uint16_t{3});
    QCOMPARE(r.controller->limSwitchParams().ccw_hard, std::uint16_t{3});
    const auto& p = s.controllerParameters();
    QCOMPARE(p.written, (std::vector<std::string>{"velocity", "jog", "home", "limit switches"}));
    QVERIFY(std::abs(p.velocity.max_velocity - 1.2) < 1e-5 && std::abs(p.velocity.acceleration - 2.0) < 5e-3);
    QVERIFY(p.jog && std::abs(p.jog->step - 0.25) < 1e-4);
    QVERIFY(std::abs(p.home_velocity - 0.8) < 1e-5);
    QVERIFY(p.limit_switches && p.limit_switches->cw_hard == 3);
    // Homing runs at the home velocity written: 5 mm at 0.8 mm/s.
    s.moveAbsolute(5.0);
    const double t0 = r.clock->now();
    s.home();
    const double a = u.aptToAcceleration(r.controller->velParams().acceleration);
    QVERIFY(std::abs(r.clock->now() - t0 -
                     trapezoidTime(5.0, u.aptToVelocity(r.controller->homeParams().velocity), a)) < 1e-6);
    // Nothing asked: nothing written, everything still read.
    Rig plain;
    plain.stage->connect();
    QVERIFY(plain.stage->controllerParameters().written.empty());
    QVERIFY(!plain.traceHas("TX 13 04") && !plain.traceHas("TX 40 04") && !plain.traceHas("TX 23 04"));
    QVERIFY(plain.traceHas("TX 41 04 01 00 50 01") && plain.traceHas("TX 24 04 01 00 50 01"));
  }

  void countsPerUnitOverrideFromTheScene() {
    fovea::StageBinding b;
    b.element = "hoe";
    b.axis = "x";
    b.controller = "KDC101";
    b.stage_model = "MTS25-Z8";
    b.soft_limits = {-10.0, 10.0};
    b.home_offset = -12.5;
    StageConfig c = stageConfigForBinding(b);
    QCOMPARE(c.stage.counts_per_unit, 34304.0);
    QVERIFY(c.stage.source.find("protocol document") != std::string::npos);
    b.counts_per_unit = 34554.96;  // the 67.49:1 gearbox figure
    b.setup.limit_switches = "breaks";
    b.setup.jog_step = 0.05;
    c = stageConfigForBinding(b);
    QCOMPARE(c.stage.counts_per_unit, 34554.96);
    QCOMPARE(c.setup.limit_switch_mode.value_or(0), std::uint16_t{3});
    QCOMPARE(c.setup.jog_step.value_or(0), 0.05);
    QVERIFY(!c.setup.max_velocity);
    QCOMPARE(apt::UnitConverter(c.controller, c.stage).positionToCounts(10.0), 345550);
  }

  void movesThatCannotBeEncodedAreRefused() {
    // Continuous rotation with absurd soft limits: 1e12 deg is 1.4e17 counts, beyond int32.
    Rig r("K10CR1", {}, std::make_pair(-1e308, 1e308));
    r.stage->connect();
    try {
      r.stage->moveAbsolute(1e12);
      QFAIL("an unencodable move was sent");
    } catch (const DeviceError& e) {
      QCOMPARE(e.kind(), DeviceError::Kind::SoftLimit);
      QVERIFY2(std::string(e.what()).find("beyond the protocol's signed 32-bit range; nothing was sent") !=
                   std::string::npos,
               e.what());
    }
    QVERIFY_THROWS_EXCEPTION(DeviceError, r.stage->moveRelative(-2e4));  // 2.7e9 counts
    QVERIFY(!r.traceHas("TX 53 04") && !r.traceHas("TX 48 04"));
    r.stage->moveRelative(15000.0);  // 2.05e9 counts: still encodable
    QVERIFY(std::abs(r.stage->state().position - 15000.0) < 1e-3);
  }

  void controllerErrorsArrivePromptly() {
    Rig r("MTS25-Z8", [](VirtualControllerConfig& c) {
      c.reject_motion = apt::ControllerResponse{0, 0x0042, "Position outside limits", true};
    });
    r.stage->connect();
    const double t0 = r.clock->now();
    try {
      r.stage->moveAbsolute(5.0);
      QFAIL("a rejected move reported success");
    } catch (const DeviceError& e) {
      QCOMPARE(e.kind(), DeviceError::Kind::Controller);
      QVERIFY2(std::string(e.what()).find("code 0x0042 (66) after MOT_MOVE_ABSOLUTE: Position outside limits") !=
                   std::string::npos,
               e.what());
    }
    QVERIFY(r.clock->now() - t0 < 0.1);  // the reply, not the move timeout
    QVERIFY(!r.stage->lastControllerError().empty());
  }

  void channelBitMaskOnTheWire() {
    auto clock = std::make_shared<SimulatedClock>();
    auto ctrl = makeVirtualController("MTS25-Z8", "", clock);
    apt::ControllerModel bits = ctrl->config().controller;
    bits.channel_bit_mask = true;
    StageConfig c = defaultStageConfig(bits, ctrl->config().stage);
    c.channel = 3;
    auto trace = std::make_shared<AptMemoryLog>();
    Stage s(std::make_unique<VirtualTransport>(ctrl, clock), c, trace);
    s.connect();
    QVERIFY(trace->lines().size() > 2);
    QCOMPARE(trace->lines()[2], std::string("TX 11 02 04 00 50 01"));  // REQ_CHANENABLESTATE, channel 3 = 0x04
  }
};

QTEST_GUILESS_MAIN(TestStageVirtual)

}  // namespace tst_stage_virtual
#include "tst_stage_virtual.moc"
