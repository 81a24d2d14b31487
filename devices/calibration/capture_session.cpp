#include "devices/calibration/capture_session.h"

#include "model/color/measurement_csv.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <future>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "devices/bench/bench.h"
#include "devices/stage/stage_binding.h"
#include "model/color/color_calibration.h"
#include "model/image/image_io.h"
#include "model/io/json_input.h"
#include "model/io/output_file.h"

namespace fovea::devices {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "fovea-capture-session";
constexpr int kVersion = 1;

std::string fileNameFor(std::size_t index, const std::string& id) {
  std::string s = id;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '+' && c != '.') c = '_';
  char prefix[32];
  std::snprintf(prefix, sizeof prefix, "%03zu_", index);
  return prefix + s + ".png";
}

nlohmann::json poseJson(const BenchPose& p) {
  return {
      {"hoe_shift_mm", p.hoe_shift_mm}, {"foveal_shift_mm", p.foveal_shift_mm}, {"camera_gaze_deg", p.camera_gaze_deg}};
}
BenchPose poseFromJson(const nlohmann::json& j) {
  BenchPose p;
  p.hoe_shift_mm = j.at("hoe_shift_mm").get<std::array<double, 2>>();
  p.foveal_shift_mm = j.at("foveal_shift_mm").get<std::array<double, 2>>();
  p.camera_gaze_deg = j.at("camera_gaze_deg").get<std::array<double, 2>>();
  return p;
}

nlohmann::json recordJson(const CaptureRecord& r) {
  nlohmann::json j{{"step", r.step},
                   {"image", r.image},
                   {"sequence", r.sequence},
                   {"exposure_start_s", r.exposure_start_s},
                   {"exposure_s", r.exposure_s},
                   {"discarded_frames", r.discarded_frames},
                   {"positions", r.positions}};
  if (r.pose) j["pose"] = poseJson(*r.pose);
  return j;
}
CaptureRecord recordFromJson(const nlohmann::json& j) {
  CaptureRecord r;
  r.step = j.at("step").get<std::string>();
  r.image = j.at("image").get<std::string>();
  r.sequence = j.value("sequence", std::uint64_t{0});
  r.exposure_start_s = j.value("exposure_start_s", 0.0);
  r.exposure_s = j.value("exposure_s", 0.0);
  r.discarded_frames = j.value("discarded_frames", 0);
  if (j.contains("positions")) r.positions = j["positions"].get<std::map<std::string, double>>();
  if (j.contains("pose")) r.pose = poseFromJson(j["pose"]);
  return r;
}

void writeAtomically(const fs::path& path, const std::string& text) {
  writeOutputFile(path, text);  // the one output writer: checked, fsync'ed, renamed while locked
}

}  // namespace

CaptureSession::CaptureSession(CaptureKind kind, std::vector<CaptureStep> plan, fs::path folder, std::string scene_name)
    : kind_(kind), plan_(std::move(plan)), folder_(std::move(folder)), scene_name_(std::move(scene_name)) {
  if (folder_.empty()) return;
  fs::create_directories(folder_);
  const fs::path manifest = folder_ / "manifest.json";
  if (!fs::exists(manifest)) {
    save();
    return;
  }
  nlohmann::json j;
  try {
    j = readJsonFile(manifest);
  } catch (const std::exception& e) {
    throw std::runtime_error(manifest.string() + ": not a capture session manifest (" + e.what() + ")");
  }
  if (j.value("format", "") != kFormat)
    throw std::runtime_error(manifest.string() + ": not a capture session manifest");
  if (j.value("kind", "") != toString(kind_))
    throw std::runtime_error(manifest.string() + ": holds a " + j.value("kind", std::string("?")) + " session, not a " +
                             toString(kind_) + " one");
  std::vector<std::string> ids, theirs;
  for (const auto& s : plan_) ids.push_back(s.id);
  for (const auto& s : j.at("steps")) theirs.push_back(s.at("id").get<std::string>());
  if (ids != theirs)
    throw std::runtime_error(manifest.string() + ": was captured with a different plan; choose another folder");
  for (const auto& r : j.value("captures", nlohmann::json::array())) records_.push_back(recordFromJson(r));
  for (const auto& m : j.value("measurements", nlohmann::json::array())) measurements_.push_back(m.get<std::string>());
  if (j.contains("gaze_calibration")) gaze_calibration_ = j["gaze_calibration"];
  if (j.contains("gaze_calibration_left")) left_gaze_calibration_ = j["gaze_calibration_left"];
}

void CaptureSession::setGazeCalibration(nlohmann::json result, nlohmann::json left) {
  gaze_calibration_ = std::move(result);
  left_gaze_calibration_ = std::move(left);
  save();
}

bool CaptureSession::done(std::size_t step) const {
  return step < plan_.size() && record(plan_[step].id) != nullptr;
}

std::optional<std::size_t> CaptureSession::nextStep() const {
  for (std::size_t i = 0; i < plan_.size(); ++i)
    if (!done(i)) return i;
  return std::nullopt;
}

const CaptureRecord* CaptureSession::record(const std::string& id) const {
  for (const auto& r : records_)
    if (r.step == id) return &r;
  return nullptr;
}

cv::Mat CaptureSession::image(const std::string& id) const {
  if (auto it = frames_.find(id); it != frames_.end()) return it->second;
  const CaptureRecord* r = record(id);
  if (!r || folder_.empty()) return {};
  const std::string path = (folder_ / r->image).string();
  try {
    return image::readCameraImage(path);  // regular, bounded, header <= 50 Mpixel, then decoded
  } catch (const image::ImageIoError&) {
    return {};  // an unreadable file: no frame
  }
}

namespace {

// Counts the axes that have sent their move. wait() returns when all have, or after a wall-clock
// second: a queued move dropped by an emergency stop never arrives, and the others must not hang.
class StartGate {
 public:
  explicit StartGate(std::size_t count) : pending_(count) {}
  void arrive() {
    {
      std::lock_guard lock(mutex_);
      if (pending_ > 0) --pending_;
    }
    cv_.notify_all();
  }
  void wait() {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, std::chrono::seconds(1), [this] { return pending_ == 0; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::size_t pending_;
};

}  // namespace

const CaptureRecord& CaptureSession::capture(std::size_t index, BenchRig& rig) {
  if (index >= plan_.size()) throw std::out_of_range("capture step index");
  if (!rig.bench || !rig.camera)
    throw DeviceError(DeviceError::Kind::Usage, "the capture rig needs a bench and a camera");
  const CaptureStep& step = plan_[index];
  if (rig.show) {
    rig.show(step.display == BenchDisplay::Peripheral ? BenchDisplay::Foveal : BenchDisplay::Peripheral,
             image::offPattern());
    rig.show(step.display, step.pattern);
  }
  // Every axis moves at once; the frame must be exposed after the last one settled. Each axis
  // sends its move, then waits at the start gate until every axis has sent its own: on a virtual
  // bench the first axis to wait advances the simulated clock, and an axis whose thread started
  // later would begin its move that much later (the moves ran one after the other or overlapped
  // by chance, so captures landed in different frames from run to run).
  std::vector<std::pair<AxisWorker*, double>> axes;
  for (const StageTarget& t : step.targets)
    if (AxisWorker* w = rig.bench->find(t.element, t.axis)) axes.emplace_back(w, elementToStage(w->binding(), t.value));
  auto settled = std::make_shared<std::vector<double>>(axes.size(), 0.0);
  auto gate = std::make_shared<StartGate>(axes.size());
  std::vector<std::future<void>> moves;
  for (std::size_t k = 0; k < axes.size(); ++k) {
    const double target = axes[k].second;
    std::future<void> f = axes[k].first->submit([target, settled, gate, k](Stage& s) {
      double duration = 0;
      try {
        duration = s.startMoveAbsolute(target);
      } catch (...) {
        gate->arrive();  // refused: the others need not wait for it
        throw;
      }
      gate->arrive();
      gate->wait();
      s.finishMove(duration);
      (*settled)[k] = s.settledAt();
    });
    moves.push_back(std::move(f));
  }
  std::exception_ptr error;
  for (auto& m : moves) {
    try {
      m.get();
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  const double settled_at = settled->empty() ? rig.camera->now() : *std::max_element(settled->begin(), settled->end());
  SettledCapture c = captureSettled(*rig.camera, settled_at);

  CaptureRecord r;
  r.step = step.id;
  r.sequence = c.frame.sequence;
  r.exposure_start_s = c.frame.exposure_start_s;
  r.exposure_s = c.frame.exposure_s;
  r.discarded_frames = c.discarded;
  for (AxisWorker* w : rig.bench->axes()) {
    const AxisSnapshot s = w->snapshot();
    if (s.state.known) r.positions[s.element + "." + s.axis] = s.element_position;
  }
  if (rig.pose) r.pose = rig.pose(c.frame.exposure_start_s);
  r.image = fileNameFor(index, step.id);
  if (!folder_.empty()) {
    try {
      image::writeCameraImage((folder_ / r.image).string(), c.frame.image);
    } catch (const image::ImageIoError& e) {
      throw std::runtime_error(std::string("cannot write the frame: ") + e.what());
    }
  }
  frames_[step.id] = c.frame.image;
  records_.push_back(r);
  save();
  return records_.back();
}

fs::path CaptureSession::importMeasurement(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(file.string() + ": cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  if (file.extension() == ".csv" || file.extension() == ".CSV") {
    // Spectroradiometer readings: averaged per level; every bad row named by its line.
    const color::MeasurementImport imp = color::importSpectroradiometerCsv(ss.str());
    if (!imp.ok())
      throw std::invalid_argument(std::to_string(imp.problems.size()) + " problem(s):\n" +
                                  color::formatProblems(imp, file.string()));
    std::string name = "measurement_" + std::to_string(measurements_.size() + 1) + "_" + file.stem().string();
    if (!folder_.empty()) {
      writeAtomically(folder_ / (name + ".csv"), ss.str());  // the readings as taken
      writeAtomically(folder_ / (name + ".json"), color::toJson(imp.measurements).dump(2) + "\n");
    }
    measurements_.push_back(name + ".json");
    save();
    return folder_.empty() ? fs::path(name + ".json") : folder_ / (name + ".json");
  }
  nlohmann::json j;
  try {
    j = readJsonText(ss.str(), file.string());
  } catch (const std::exception& e) {
    throw std::invalid_argument(file.string() + ": not JSON (" + e.what() + ")");
  }
  if (kind_ == CaptureKind::Color) color::parseColorMeasurements(j);  // throws naming the key
  std::string name = "measurement_" + std::to_string(measurements_.size() + 1) + "_" + file.filename().string();
  if (!folder_.empty()) writeAtomically(folder_ / name, ss.str());
  measurements_.push_back(name);
  save();
  return folder_.empty() ? fs::path(name) : folder_ / name;
}

nlohmann::json CaptureSession::manifest() const {
  nlohmann::json steps = nlohmann::json::array(), captures = nlohmann::json::array();
  for (const auto& s : plan_) steps.push_back(toJson(s));
  for (const auto& r : records_) captures.push_back(recordJson(r));
  nlohmann::json j{{"format", kFormat}, {"version", kVersion},  {"kind", toString(kind_)},      {"scene", scene_name_},
                   {"steps", steps},    {"captures", captures}, {"measurements", measurements_}};
  if (!gaze_calibration_.is_null()) j["gaze_calibration"] = gaze_calibration_;
  if (!left_gaze_calibration_.is_null()) j["gaze_calibration_left"] = left_gaze_calibration_;
  return j;
}

void CaptureSession::save() const {
  if (folder_.empty()) return;
  writeAtomically(folder_ / "manifest.json", manifest().dump(2) + "\n");
}

}  // namespace fovea::devices
