// fovea-cli stage (--virtual MODEL | --serial SERIAL) [--channel N] [--trace FILE] [--json]
//                 COMMAND [ARG]
// COMMAND: info, enable, disable, home, move-abs MM, move-rel MM, jog forward|reverse,
// stop [--immediate], position. Rotation stages take and report degrees instead of mm.
//
// Exit codes: 0 done; 2 invalid arguments or a move outside the soft limits (nothing is
// sent); 3 the device does not answer (timeout), is not on the bus, or vanished; 1 device
// state problems (not homed, channel disabled, limit switch hit, malformed reply).
//
// Soft limits: those of the scene's stage binding with the device's serial (element limits
// minus home offset, within the stage travel), else the stage's travel; --soft-limits A,B
// overrides.
//
// Virtual devices: every invocation starts a fresh emulator (simulated clock, so moves
// complete instantly) in a defined power-on state: channel enabled, homed, and at the
// scene's nominal pose when a stage binding matches (element coordinate 0 = stage reading
// -home_offset, e.g. 12.5 mm for the prototype's HOE stages), else at 0 (the home switch). MODEL is a stage (MTS25-Z8,
// Z825B, DDSM50, K10CR1) or a controller (KDC101, TDC001, KBD101); the scene binding with that model supplies serial
// and soft limits.
// --virtual-fault mute makes the emulator swallow every message (to exercise timeouts);
// --virtual-fault reject makes it answer every motion command with HW_RICHRESPONSE (to
// exercise controller errors, reported in the controller's words, exit 1).
// --transcript FILE records every message with its link-clock time (devices/replay).
// --replay TRANSCRIPT plays a recorded transcript as the device (devices/replay/
// replay_transport.h) instead of the USB link or the emulator: the device is named as when it
// was recorded (--serial SERIAL or --virtual MODEL); a host message that differs from the
// transcript's is a protocol error naming the line (exit 1).
// --trace and --transcript are written (atomically, by the one output writer) once the
// command has talked to the device; a command refused before any byte leaves them untouched.
// They must name different files (exit 2).
//
// Refused before any byte (exit 2): targets outside the soft limits or the stage's travel
// (whatever --soft-limits says; an override is intersected with the travel), targets and
// distances that do not fit the protocol's signed 32-bit counts, --soft-limits MIN,MAX with
// MIN >= MAX, a --timeout outside (0, 3600] s.
#include <cmath>
#include <functional>
#include <iostream>
#include <mutex>
#include <optional>
#include <span>
#include <tuple>

#include "app/cli/cli_common.h"
#include "devices/replay/replay_transport.h"
#include "devices/replay/transcript.h"
#include "devices/stage/stage.h"
#include "devices/stage/stage_binding.h"
#include "devices/transport/libusb_transport.h"
#include "devices/virtual/virtual_transport.h"
#include "model/io/output_file.h"

namespace fovea::cli {
namespace cmd_stage {  // one per command file: fovea-cli compiles in unity batches
namespace {

using devices::DeviceError;

struct StageArgs {
  std::string virtual_model, serial, trace, transcript, replay, command, arg, scene, fault, soft_limits;
  bool trace_given = false, transcript_given = false, replay_given = false;
  int channel = 1;
  bool json = false, immediate = false;
  double timeout_s = 2.0;
};

constexpr double kMaxTimeout_s = 3600.0;

// A log sink that keeps its lines in memory; the file is written once, at the end, by the one
// output writer (checked, atomic): a refused command or a full disk never leaves it truncated.
class BufferedLog : public devices::AptLogSink {
 public:
  BufferedLog(std::string path, std::string header, std::function<double()> clock)
      : path_(std::move(path)), text_(std::move(header)), clock_(std::move(clock)), t0_(clock_ ? clock_() : 0.0) {}
  void message(bool transmitted, std::span<const std::uint8_t> raw) override {
    std::lock_guard lock(mutex_);
    text_ +=
        (clock_ ? devices::transcriptLine(clock_() - t0_, transmitted, raw) : devices::aptLogLine(transmitted, raw)) +
        "\n";
  }
  void write() {
    std::lock_guard lock(mutex_);
    writeOutputFile(path_, text_);
  }

 private:
  std::mutex mutex_;
  std::string path_, text_;
  std::function<double()> clock_;
  double t0_ = 0;
};

int exitCodeFor(DeviceError::Kind k) {
  switch (k) {
    case DeviceError::Kind::SoftLimit:
    case DeviceError::Kind::Usage:
      return 2;
    case DeviceError::Kind::Timeout:
    case DeviceError::Kind::NotFound:
    case DeviceError::Kind::Disconnected:
    case DeviceError::Kind::Io:
      return 3;
    default:
      return 1;
  }
}

double parseDistance(const StageArgs& a, const std::string& unit) {
  if (a.arg.empty()) usageError(a.command + " needs a distance in " + unit);
  return parseNumberList(a.arg, a.command + " " + unit, 1, 1)[0];
}

nlohmann::json stateJson(const devices::Stage& s, const devices::AxisState& st) {
  const std::string unit = s.config().stage.unit();
  nlohmann::json j{{"unit", unit},
                   {"known", st.known},
                   {"position", st.position},
                   {"position_" + unit, st.position},
                   {"homed", st.homed},
                   {"enabled", st.enabled},
                   {"moving", st.moving},
                   {"forward_limit", st.forward_limit},
                   {"reverse_limit", st.reverse_limit},
                   {"status_bits", st.bits}};
  return j;
}

// What the controller reported on connect (after the writes the scene asked for).
nlohmann::json controllerSetupJson(const devices::Stage& s) {
  const std::string unit = s.config().stage.unit();
  const devices::ControllerParameters& p = s.controllerParameters();
  nlohmann::json j{{"velocity",
                    {{"max_" + unit + "_per_s", p.velocity.max_velocity},
                     {"acceleration_" + unit + "_per_s2", p.velocity.acceleration}}},
                   {"written", p.written}};
  if (p.jog)
    j["jog"] = {{"mode", p.jog->continuous ? "continuous" : "single-step"},
                {"step_" + unit, p.jog->step},
                {"max_" + unit + "_per_s", p.jog->max_velocity},
                {"acceleration_" + unit + "_per_s2", p.jog->acceleration},
                {"stop", p.jog->immediate_stop ? "immediate" : "profiled"}};
  else
    j["jog"] = nullptr;
  if (p.home)
    j["home"] = {{"direction", p.home->direction == 1 ? "forward" : "reverse"},
                 {"limit_switch", p.home->limit_switch},
                 {"velocity_" + unit + "_per_s", p.home_velocity},
                 {"offset_" + unit, p.home_offset}};
  else
    j["home"] = "not reported by the controller";
  if (p.limit_switches)
    j["limit_switches"] = {{"cw_hard", p.limit_switches->cw_hard},
                           {"ccw_hard", p.limit_switches->ccw_hard},
                           {"soft_limit_mode", p.limit_switches->soft_mode}};
  else
    j["limit_switches"] = "not reported by the controller";
  return j;
}

void run(const StageArgs& a) {
  if (a.virtual_model.empty() == a.serial.empty()) usageError("give exactly one of --virtual MODEL or --serial SERIAL");
  if (a.channel < 1 || a.channel > 4) usageError("--channel: expected 1 to 4, got " + std::to_string(a.channel));
  if (!(a.timeout_s > 0 && a.timeout_s <= kMaxTimeout_s)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "--timeout: expected seconds in (0, %.0f], got %g", kMaxTimeout_s, a.timeout_s);
    usageError(buf);
  }
  static const std::vector<std::string> commands = {"info",     "enable", "disable", "home",    "move-abs",
                                                    "move-rel", "jog",    "stop",    "position"};
  if (std::find(commands.begin(), commands.end(), a.command) == commands.end())
    usageError("unknown stage command '" + a.command +
               "' (info, enable, disable, home, move-abs MM, move-rel MM, jog forward|reverse, stop, position)");
  if (!a.fault.empty() && a.fault != "mute" && a.fault != "reject")
    usageError("--virtual-fault: expected 'mute' or 'reject', got '" + a.fault + "'");
  for (const auto& [given, name, path] :
       {std::tuple{a.trace_given, "--trace", a.trace}, std::tuple{a.transcript_given, "--transcript", a.transcript}}) {
    if (!given) continue;
    if (path.empty()) usageError(std::string(name) + ": an empty path names no file");
    if (const auto why = outputPathProblem(path)) usageError(std::string(name) + ": " + path + ": " + *why);
  }
  checkDistinctOutputs({{"--trace", a.trace}, {"--transcript", a.transcript}, {"--replay", a.replay}});
  if (a.replay_given && a.replay.empty()) usageError("--replay: an empty path names no file");
  if (a.replay_given && !a.fault.empty()) usageError("--replay and --virtual-fault exclude each other");
  std::vector<devices::TranscriptEntry> replay;
  if (a.replay_given) {
    try {
      replay = devices::readTranscriptFile(a.replay);
    } catch (const std::invalid_argument& e) {
      inputError(std::string("--replay: ") + e.what());
    }
  }

  const Scene scene = loadSceneOrExit(a.scene);
  std::optional<StageBinding> binding;
  std::unique_ptr<devices::Transport> transport;
  std::optional<apt::ControllerModel> controller;
  std::optional<apt::StageModel> stage;
  std::shared_ptr<devices::VirtualAptController> emulator;

  if (!a.virtual_model.empty()) {
    for (const auto& b : scene.stages)
      if (!binding && (b.stage_model == a.virtual_model || b.controller == a.virtual_model)) binding = b;
    auto clock = std::make_shared<devices::SimulatedClock>();
    try {
      emulator = binding ? devices::makeVirtualController(binding->stage_model, binding->serial, clock)
                         : devices::makeVirtualController(a.virtual_model, "", clock);
    } catch (const DeviceError& e) {
      usageError(std::string("--virtual: ") + e.what());
    }
    auto cfg = emulator->config();
    if (binding) {
      if (auto c = apt::findController(binding->controller)) cfg.controller = *c;
      // A bound virtual stage powers up homed at the scene's nominal pose: element
      // coordinate 0, i.e. stage reading -home_offset (kept inside the travel).
      cfg.position =
          std::clamp(devices::elementToStage(*binding, 0.0), cfg.stage.continuous ? -1e9 : cfg.stage.travel_min,
                     cfg.stage.continuous ? 1e9 : cfg.stage.travel_max);
    }
    if (a.fault == "reject")
      cfg.reject_motion = apt::ControllerResponse{0, 0x0001, "virtual fault: motion command rejected", true};
    emulator = std::make_shared<devices::VirtualAptController>(cfg, clock);
    emulator->setMute(a.fault == "mute");
    controller = emulator->config().controller;
    stage = emulator->config().stage;
    transport = std::make_unique<devices::VirtualTransport>(emulator, clock);
  } else {
    for (const auto& b : scene.stages)
      if (!binding && b.serial == a.serial) binding = b;
    controller = binding ? apt::findController(binding->controller) : apt::controllerForSerial(a.serial);
    if (!controller)
      usageError("--serial " + a.serial +
                 ": not a Thorlabs controller serial this tool knows (27.. KDC101, 83.. TDC001, 28.. KBD101, 55.. "
                 "K10CR1) and no scene binding names it");
    stage = apt::findStage(binding ? binding->stage_model : controller->default_stage);
    if (!stage) usageError("--serial " + a.serial + ": unknown stage model in the scene binding");
    transport = std::make_unique<devices::LibusbTransport>(a.serial);
  }

  devices::StageConfig config = devices::defaultStageConfig(*controller, *stage);
  if (binding) {
    try {
      config = devices::stageConfigForBinding(*binding);
    } catch (const DeviceError& e) {
      inputError(e.what());
    }
  }
  if (!a.soft_limits.empty()) {
    const auto l = parseNumberList(a.soft_limits, "--soft-limits", 2, 2);
    if (!(l[0] < l[1]))
      usageError("--soft-limits " + a.soft_limits + ": expected MIN,MAX with MIN < MAX (" + stage->unit() + ")");
    // An override narrows, never widens, what the stage can do: intersect with its travel.
    config.soft_min = stage->continuous ? l[0] : std::max(l[0], stage->travel_min);
    config.soft_max = stage->continuous ? l[1] : std::min(l[1], stage->travel_max);
    if (!(config.soft_min < config.soft_max)) {
      char buf[256];
      std::snprintf(buf, sizeof buf, "--soft-limits %s: no overlap with the travel [%g, %g] %s of the %s",
                    a.soft_limits.c_str(), stage->travel_min, stage->travel_max, stage->unit().c_str(),
                    stage->name.c_str());
      usageError(buf);
    }
  }
  if (a.replay_given) {
    // The recorded session plays the device's side: the same controller and stage, the link
    // replaced.
    devices::DeviceInfo info;
    info.model = controller->name;
    info.serial = emulator ? emulator->config().serial : a.serial;
    info.description = "replay of " + a.replay;
    transport = std::make_unique<devices::ReplayTransport>(std::move(replay), info, a.replay);
  }
  config.channel = static_cast<std::uint8_t>(a.channel);
  config.reply_timeout = std::chrono::milliseconds(static_cast<long>(a.timeout_s * 1000));

  std::shared_ptr<devices::AptLogSink> trace;
  std::vector<std::shared_ptr<BufferedLog>> logs;
  if (a.trace_given) logs.push_back(std::make_shared<BufferedLog>(a.trace, "", nullptr));
  if (a.transcript_given) {
    devices::Transport* link = transport.get();
    logs.push_back(std::make_shared<BufferedLog>(
        a.transcript,
        "# fovea APT transcript: seconds since the link opened, TX/RX bytes (see devices/replay/transcript.h)\n",
        [link] { return link->now(); }));
  }
  if (logs.size() == 1) trace = logs[0];
  if (logs.size() == 2)
    trace = std::make_shared<devices::TraceFanout>(
        std::vector<std::shared_ptr<devices::AptLogSink>>(logs.begin(), logs.end()));
  // Written once the device was talked to, whatever the outcome (a timeout's trace is the
  // evidence); a failed write is exit 1 naming the file.
  const auto writeLogs = [&logs] {
    for (const auto& l : logs) {
      try {
        l->write();
      } catch (const OutputError& e) {
        inputError(e.what());
      }
    }
  };
  const std::string unit = stage->unit();
  // Absolute targets are checked before anything touches the device.
  std::optional<double> target;
  if (a.command == "move-abs" || a.command == "move-rel") target = parseDistance(a, unit);
  std::optional<apt::JogDirection> jog;
  if (a.command == "jog") {
    if (a.arg == "forward")
      jog = apt::JogDirection::Forward;
    else if (a.arg == "reverse")
      jog = apt::JogDirection::Reverse;
    else
      usageError("jog: expected 'forward' or 'reverse', got '" + a.arg + "'");
  }

  auto* replay_link = dynamic_cast<devices::ReplayTransport*>(transport.get());
  devices::Stage s(std::move(transport), config, trace);
  nlohmann::json out;
  bool talked = false;
  try {
    // The same checks as Stage::startMove*, before even opening the link.
    const std::string device = controller->name + " " + (emulator ? emulator->config().serial : a.serial);
    if (a.command == "move-abs") devices::checkMoveTarget(config, *target, "move", device);
    if (a.command == "move-rel") {
      if (!std::isfinite(*target)) throw DeviceError(DeviceError::Kind::Usage, "move-rel: distance is not finite");
      char what[96];
      std::snprintf(what, sizeof what, "relative move by %.4f %s", *target, unit.c_str());
      devices::checkEncodable(config, *target, what);
    }
    talked = true;
    s.connect();
    if (a.command == "enable")
      s.setEnabled(true);
    else if (a.command == "disable")
      s.setEnabled(false);
    else if (a.command == "home")
      s.home();
    else if (a.command == "move-abs")
      s.moveAbsolute(*target);
    else if (a.command == "move-rel")
      s.moveRelative(*target);
    else if (a.command == "jog")
      s.jog(*jog);
    else if (a.command == "stop")
      s.stop(a.immediate);
    const devices::AxisState st = s.poll();
    out = stateJson(s, st);
    if (a.command == "info") {
      const auto hw = s.hardwareInfo();
      const auto vel = s.velocity();
      out["hardware"] = {{"model", hw.model},
                         {"serial", std::to_string(hw.serial)},
                         {"firmware", std::to_string(hw.fw_major) + "." + std::to_string(hw.fw_interim) + "." +
                                          std::to_string(hw.fw_minor)},
                         {"notes", hw.notes},
                         {"channels", hw.channels}};
      out["velocity"] = {{"max_" + unit + "_per_s", vel.max_velocity},
                         {"acceleration_" + unit + "_per_s2", vel.acceleration}};
      out["controller_setup"] = controllerSetupJson(s);
      out["counts_per_" + unit] = config.stage.counts_per_unit;
      out["counts_source"] = config.stage.source;
    }
  } catch (const DeviceError& e) {
    if (talked) {
      try {
        s.disconnect();
      } catch (...) {  // the device error is the one to report
      }
      writeLogs();
    }
    throw CliError(exitCodeFor(e.kind()), e.what());
  }
  if (replay_link) out["replay"] = {{"file", a.replay}, {"entries_not_played", replay_link->remaining()}};
  s.disconnect();
  writeLogs();
  out["command"] = a.command;
  out["device"] = {{"kind", "stage-controller"},
                   {"model", controller->name},
                   {"serial", emulator ? emulator->config().serial : a.serial},
                   {"virtual", emulator != nullptr},
                   {"stage_model", stage->name},
                   {"channel", a.channel}};
  if (binding)
    out["binding"] = {{"element", binding->element}, {"axis", binding->axis}, {"home_offset", binding->home_offset}};
  out["soft_limits_" + unit] = {config.soft_min, config.soft_max};
  if (a.json) {
    printJson(out);
    return;
  }
  std::printf("%s %s%s (%s): %s %.4f %s, %s, %s%s\n", controller->name.c_str(),
              out["device"]["serial"].get<std::string>().c_str(), emulator ? " virtual" : "", stage->name.c_str(),
              a.command == "position" ? "position" : (a.command + " done, position").c_str(),
              out["position"].get<double>(), unit.c_str(), out["homed"].get<bool>() ? "homed" : "not homed",
              out["enabled"].get<bool>() ? "enabled" : "disabled", out["moving"].get<bool>() ? ", moving" : "");
  if (out.contains("hardware"))
    std::printf("  hardware %s serial %s firmware %s, %s\n", out["hardware"]["model"].get<std::string>().c_str(),
                out["hardware"]["serial"].get<std::string>().c_str(),
                out["hardware"]["firmware"].get<std::string>().c_str(),
                out["hardware"]["notes"].get<std::string>().c_str());
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("stage", "Drive one motorised stage (APT protocol) on USB or on the virtual bench");
  auto a = std::make_shared<StageArgs>();
  auto* v = cmd->add_option("--virtual", a->virtual_model,
                            "virtual device: stage or controller model (MTS25-Z8, K10CR1, KDC101, ...)");
  auto* s = cmd->add_option("--serial", a->serial, "serial number of a USB controller");
  v->excludes(s);
  cmd->add_option("--channel", a->channel, "controller channel (default 1)");
  auto* trace = cmd->add_option("--trace", a->trace, "write every APT message as 'TX|RX HH HH ...' lines to FILE");
  cmd->add_flag("--json", a->json, "print the result as JSON");
  cmd->add_flag("--immediate", a->immediate, "stop: immediate instead of profiled");
  cmd->add_option("--scene", a->scene, "scene with the stage bindings (default: the prototype bench)");
  cmd->add_option("--timeout", a->timeout_s, "seconds to wait for each reply (default 2)");
  cmd->add_option("--soft-limits", a->soft_limits, "override the soft limits: MIN,MAX in mm (deg)");
  cmd->add_option("--virtual-fault", a->fault,
                  "make the virtual device misbehave: mute (never answers), reject (HW_RICHRESPONSE to every move)");
  auto* transcript =
      cmd->add_option("--transcript", a->transcript,
                      "write every APT message as 'SECONDS TX|RX HH HH ...' lines to FILE (a replayable transcript)");
  auto* replay = cmd->add_option("--replay", a->replay,
                                 "play a recorded transcript as the device (name it with --serial or --virtual as "
                                 "when it was recorded)");
  cmd->add_option("COMMAND", a->command, "info|enable|disable|home|move-abs|move-rel|jog|stop|position")->required();
  cmd->add_option("ARG", a->arg, "distance in mm (deg) for move-abs/move-rel, forward|reverse for jog");
  cmd->positionals_at_end(false);
  cmd->callback([a, trace, transcript, replay] {
    a->trace_given = trace->count() > 0;
    a->transcript_given = transcript->count() > 0;
    a->replay_given = replay->count() > 0;
    run(*a);
  });
}

const Registrar reg{"stage", &install};

}  // namespace
}  // namespace cmd_stage
}  // namespace fovea::cli
