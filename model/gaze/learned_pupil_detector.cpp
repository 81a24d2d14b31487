#include "model/gaze/learned_pupil_detector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <system_error>

#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "fovea/pupil_model_paths.h"

namespace fovea::gaze {

struct LearnedPupilDetector::Net {
  cv::dnn::Net dnn, refine;
};

namespace {

cv::dnn::Net loadNet(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error("pupil model " + path + ": no such file");
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("pupil model " + path + ": not a readable ONNX model (" + e.msg + ")");
  }
  if (net.empty()) throw std::runtime_error("pupil model " + path + ": empty network");
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  return net;
}

using Outputs = std::array<double, kLearnedPupilOutputs>;

// One pass of a stage over a batch of 96 x 96 inputs (x / 255 - 0.5, as
// scripts/train_pupil_net.py feeds them). Outputs per input: centre x, y, axes, cos 2θ, sin 2θ,
// visibility logit.
std::vector<Outputs> run(cv::dnn::Net& net, const std::vector<cv::Mat>& batch, const std::string& path) {
  net.setInput(cv::dnn::blobFromImages(batch, 1.0 / 255, {}, cv::Scalar(127.5), false, false, CV_32F));
  const cv::Mat out = net.forward();
  if (out.total() != batch.size() * kLearnedPupilOutputs)
    throw std::runtime_error("pupil model " + path + ": expected 7 outputs per frame");
  std::vector<Outputs> r(batch.size());
  const float* a = out.ptr<float>();
  for (auto& o : r)
    for (double& v : o) v = *a++;
  return r;
}

cv::Mat mirrored(const cv::Mat& input) {
  cv::Mat m;
  cv::flip(input, m, 1);
  return m;
}

// Test-time flip augmentation (a mirrored eye is an eye; both stages were trained with
// horizontal flips): `a` of the input and `b` of its mirror image, b mapped back and the two
// averaged. A centre fraction f mirrors to `mirror` - f: (side - 1) / side for the full frame,
// whose labels put pixel centres at integers (OpenCV's convention), 1 for a refining window,
// whose fractions are of its pixel edges; the mirror takes θ to -θ: sin 2θ changes sign, cos 2θ
// does not. The average is symmetric in the two, so a frame and its mirror image get the same
// visibility and the mirrored ellipse.
Outputs flipAverage(const Outputs& a, const Outputs& b, double mirror) {
  return {0.5 * (a[0] + mirror - b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]), 0.5 * (a[3] + b[3]),
          0.5 * (a[4] + b[4]),          0.5 * (a[5] - b[5]), 0.5 * (a[6] + b[6])};
}

// One pass of a stage, or with `mirror` the input and its mirror image as one batch of two
// (cheaper than two passes), flip-averaged.
Outputs forward(cv::dnn::Net& net, const cv::Mat& input, std::optional<double> mirror, const std::string& path) {
  if (!mirror) return run(net, {input}, path)[0];
  const auto r = run(net, {input, mirrored(input)}, path);
  return flipAverage(r[0], r[1], *mirror);
}

}  // namespace

std::vector<std::string> pupilModelCandidates() {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  if (const char* env = std::getenv("FOVEA_PUPIL_MODEL"); env && *env) return {env};  // an explicit choice only
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) out.push_back((exe.parent_path().parent_path() / FOVEA_PUPIL_MODEL_INSTALL_REL).string());
  out.emplace_back(FOVEA_PUPIL_MODEL_INSTALL_PATH);
  out.emplace_back(FOVEA_PUPIL_MODEL_SOURCE_PATH);
  return out;
}

std::string findPupilModel() {
  const auto candidates = pupilModelCandidates();
  std::string tried;
  for (const auto& p : candidates) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(p, ec)) return p;
    tried += (tried.empty() ? "" : ", ") + p;
  }
  throw std::runtime_error("pupil model pupil-net.onnx not found (tried " + tried +
                           "; set FOVEA_PUPIL_MODEL or run scripts/train-pupil-net.sh)");
}

LearnedPupilDetector::LearnedPupilDetector(const std::string& model_path)
    : net_(std::make_unique<Net>()), path_(model_path.empty() ? findPupilModel() : model_path) {
  net_->dnn = loadNet(path_);
  // The refining stage beside the model; a file there that does not load is an error, not a
  // silent fall-back to one stage.
  std::error_code ec;
  const auto refine = std::filesystem::path(path_).parent_path() / "pupil-refine.onnx";
  if (std::filesystem::is_regular_file(refine, ec)) {
    refine_path_ = refine.string();
    net_->refine = loadNet(refine_path_);
  }
}

LearnedPupilDetector::~LearnedPupilDetector() = default;
LearnedPupilDetector::LearnedPupilDetector(LearnedPupilDetector&&) noexcept = default;
LearnedPupilDetector& LearnedPupilDetector::operator=(LearnedPupilDetector&&) noexcept = default;

PupilDetection LearnedPupilDetector::detect(const cv::Mat& image, double min_confidence, double refine_scale_above) {
  const auto refused = [](const char* reason) {
    PupilDetection r;
    r.reason = reason;
    return r;
  };
  if (image.empty()) return refused("empty frame");
  const cv::Mat grey = toGrey8(image);
  if (grey.empty()) return refused("unsupported image type");
  if (grey.cols < 16 || grey.rows < 16) return refused("frame too small");
  PupilDetection d;
  // Square the frame (the network was trained on square frames), then downscale.
  const int side = std::max(grey.cols, grey.rows);
  const int pad_x = (side - grey.cols) / 2, pad_y = (side - grey.rows) / 2;
  cv::Mat square = grey;
  if (pad_x || pad_y)
    cv::copyMakeBorder(grey, square, pad_y, side - grey.rows - pad_y, pad_x, side - grey.cols - pad_x,
                       cv::BORDER_REPLICATE);
  cv::Mat small;
  cv::resize(square, small, {kLearnedPupilInputPx, kLearnedPupilInputPx}, 0, 0, cv::INTER_AREA);
  // A frame without contrast (lens cap, saturated, uniform) has no pupil, whatever the
  // network says of it (trained only on eyes): 4 DN of standard deviation at 96 px.
  cv::Scalar mean, sd;
  cv::meanStdDev(small, mean, sd);
  if (sd[0] < 4) return refused("no contrast in the frame (lens cap, saturated or uniform)");
  // The full-frame stage alone decides whether there is a pupil. Alone it runs the frame and its
  // mirror image (test-time flip). Before a refining stage it runs the frame, and the mirror
  // image only when the visibility logit is within kFirstStageFlipBandLogit of the threshold's:
  // there the averaged logit decides, elsewhere the one pass, whose decision the average would
  // turn only if the mirror's logit lay further than the band on the other side (so a frame and
  // its mirror image are found alike unless their passes' logits differ by more than twice the
  // band). The refining stage places the centre; the first stage's only places its
  // window, and the flip moved it too little to matter (docs/gaze-tracking.md, Google Benchmark:
  // the flip cost ~0.5 ms a frame).
  const double mirror_full = (side - 1.0) / side;
  const bool two_stages = !net_->refine.empty();
  auto o = forward(net_->dnn, small, two_stages ? std::nullopt : std::optional(mirror_full), path_);
  const double threshold_logit = std::log(min_confidence / (1.0 - min_confidence));
  if (two_stages && std::abs(o[6] - threshold_logit) <= kFirstStageFlipBandLogit)
    o = flipAverage(o, run(net_->dnn, {mirrored(small)}, path_)[0], mirror_full);
  d.confidence = 1.0 / (1.0 + std::exp(-o[6]));
  if (d.confidence < min_confidence) {
    d.reason = "no pupil (learned detector's confidence below the threshold)";
    d.confidence = 0;
    return d;
  }
  d.found = true;
  double cx = o[0] * side, cy = o[1] * side, major = o[2] * side, minor = o[3] * side;
  if (!net_->refine.empty()) {
    // The refining window (scripts/train_pupil_net.py, refine_crops and scaled_canvas): the
    // square frame at 200 px, shrunk to c = round(200 T / m) px when the proposed major axis m
    // exceeds T = kRefineScaleAboveMajor of the window's span at 200 px (192 px of a 400 px
    // frame; 200 -> c with INTER_AREA, the trainer's two steps). Square -> canvas takes X to
    // u = (X + 0.5) / s - 0.5, s = side / c (OpenCV's resize maps pixel centres so at any size);
    // the window starts at round(u - 47.5) (cvRound rounds half to even, symmetrically: a
    // mirrored frame's window is the mirrored window, and the first stage's centre is
    // mirror-equivariant) and a window fraction f is X = (96 f + start) s - 0.5. Edges
    // replicated, as in training.
    const double scale_above_px = refine_scale_above * kLearnedPupilInputPx * side / kLearnedPupilCanvasPx;
    const double proposed_major = std::max(major, minor);
    int c = kLearnedPupilCanvasPx;
    if (scale_above_px > 0 && proposed_major > scale_above_px)
      c = std::max(kLearnedPupilInputPx, cvRound(kLearnedPupilCanvasPx * scale_above_px / proposed_major));
    const double s = static_cast<double>(side) / c;
    const auto start = [&](double x) {
      return std::clamp(cvRound((x + 0.5) / s - 0.5 - (kLearnedPupilInputPx - 1) / 2.0), -kLearnedPupilInputPx, c);
    };
    const int ox = start(cx), oy = start(cy);
    cv::Mat canvas, padded;
    cv::resize(square, canvas, {kLearnedPupilCanvasPx, kLearnedPupilCanvasPx}, 0, 0, cv::INTER_AREA);
    if (c != kLearnedPupilCanvasPx) cv::resize(cv::Mat(canvas), canvas, {c, c}, 0, 0, cv::INTER_AREA);
    cv::copyMakeBorder(canvas, padded, kLearnedPupilInputPx, kLearnedPupilInputPx, kLearnedPupilInputPx,
                       kLearnedPupilInputPx, cv::BORDER_REPLICATE);
    const cv::Mat window = padded(cv::Rect(ox + kLearnedPupilInputPx, oy + kLearnedPupilInputPx, kLearnedPupilInputPx,
                                           kLearnedPupilInputPx))
                               .clone();
    // One pass. The flipped pair for pupils wider than half the window (the eighth session's rule)
    // is not needed beside the scaled window: with it the hard set placed 95.3 / 96.8 / 95.7 % of
    // its centres within 5 px at seeds 5 / 2026 / 99, without it 95.5 / 96.3 / 95.2 %, and every
    // frame costs one pass of each stage (docs/gaze-tracking.md, *Where the flips run*).
    const double span = kLearnedPupilInputPx * s;  // frame px per window unit
    const auto r = forward(net_->refine, window, std::nullopt, refine_path_);
    cx = (kLearnedPupilInputPx * r[0] + ox) * s - 0.5;
    cy = (kLearnedPupilInputPx * r[1] + oy) * s - 0.5;
    major = r[2] * span, minor = r[3] * span;
    o[4] = r[4], o[5] = r[5];
  }
  d.ellipse.centre = {cx - pad_x, cy - pad_y};
  // The doubled angle (the ellipse is symmetric under a half turn) back to degrees.
  double angle = 0.5 * std::atan2(o[5], o[4]) * 180 / std::numbers::pi;
  if (minor > major) std::swap(major, minor), angle += 90;
  d.ellipse.major_px = std::max(major, 0.0);
  d.ellipse.minor_px = std::max(minor, 0.0);
  d.ellipse.angle_deg = std::fmod(angle + 360, 180.0);
  return d;
}

}  // namespace fovea::gaze
