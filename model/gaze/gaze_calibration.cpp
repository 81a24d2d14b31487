#include "model/gaze/gaze_calibration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/QR>

#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea::gaze {

namespace {

Eigen::RowVectorXd terms(GazeModel m, double u, double v) {
  Eigen::RowVectorXd t(termCount(m));
  t[0] = 1;
  t[1] = u;
  t[2] = v;
  if (m == GazeModel::Bilinear || m == GazeModel::Poly2) t[3] = u * v;
  if (m == GazeModel::Poly2) {
    t[4] = u * u;
    t[5] = v * v;
  }
  return t;
}

Eigen::Vector2d jsonPoint(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 2) throw std::invalid_argument(where + " must be [x, y]");
  Eigen::Vector2d p;
  for (int k = 0; k < 2; ++k) {
    if (!j[k].is_number()) throw std::invalid_argument(where + " must hold two finite numbers");
    p[k] = j[k].get<double>();
    if (!std::isfinite(p[k])) throw std::invalid_argument(where + " is not finite");
  }
  return p;
}

// RMS-S2S and SD (degrees) of a sequence of gaze estimates.
std::pair<double, double> precision(const std::vector<std::array<double, 2>>& g) {
  if (g.size() < 2) return {0.0, 0.0};
  double s2s = 0;
  for (std::size_t i = 1; i < g.size(); ++i) s2s += std::pow(angleBetweenDeg(g[i - 1], g[i]), 2);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& e : g) mean += gazeDirection(e[0], e[1]);
  mean.normalize();
  double sd = 0;
  for (const auto& e : g) {
    const double c = std::clamp(mean.dot(gazeDirection(e[0], e[1])), -1.0, 1.0);
    sd += std::pow(radToDeg(std::acos(c)), 2);
  }
  return {std::sqrt(s2s / static_cast<double>(g.size() - 1)), std::sqrt(sd / static_cast<double>(g.size()))};
}

TargetResult evaluate(const GazeMap& map, const GazeTarget& t, int average) {
  TargetResult r;
  r.label = t.label;
  r.target_deg = t.target_deg;
  r.estimate_deg = map.gazeDeg(averagedPupil(t.pupil_px, average));
  r.error_deg = angleBetweenDeg(r.target_deg, r.estimate_deg);
  std::vector<std::array<double, 2>> est;
  est.reserve(t.pupil_px.size());
  for (const auto& p : t.pupil_px) est.push_back(map.gazeDeg(p));
  std::tie(r.precision_rms_s2s_deg, r.precision_sd_deg) = precision(est);
  r.samples = static_cast<int>(t.pupil_px.size());
  r.holdout = t.holdout;
  return r;
}
}  // namespace

const char* modelName(GazeModel m) {
  switch (m) {
    case GazeModel::Poly1:
      return "poly1";
    case GazeModel::Bilinear:
      return "bilinear";
    case GazeModel::Poly2:
      return "poly2";
  }
  return "?";
}

std::optional<GazeModel> modelFromName(const std::string& n) {
  if (n == "poly1") return GazeModel::Poly1;
  if (n == "bilinear") return GazeModel::Bilinear;
  if (n == "poly2") return GazeModel::Poly2;
  return std::nullopt;
}

int termCount(GazeModel m) {
  return m == GazeModel::Poly1 ? 3 : m == GazeModel::Bilinear ? 4 : 6;
}

std::vector<std::string> termNames(GazeModel m) {
  std::vector<std::string> all{"1", "u", "v", "uv", "u^2", "v^2"};
  all.resize(static_cast<std::size_t>(termCount(m)));
  return all;
}

GazeModel defaultModel(int n) {
  return n >= 9 ? GazeModel::Poly2 : n >= 5 ? GazeModel::Bilinear : GazeModel::Poly1;
}

std::vector<GazeTarget> parseGazeSamples(const nlohmann::json& j) {
  if (!j.is_object()) throw std::invalid_argument("the samples file must be a JSON object");
  if (j.contains("format") && j["format"] != "fovea-gaze-samples")
    throw std::invalid_argument("format must be \"fovea-gaze-samples\"");
  if (j.contains("version") && j["version"] != 1) throw std::invalid_argument("version must be 1");
  if (!j.contains("targets") || !j["targets"].is_array() || j["targets"].empty())
    throw std::invalid_argument("needs a non-empty \"targets\" array");
  std::vector<GazeTarget> out;
  for (std::size_t i = 0; i < j["targets"].size(); ++i) {
    const auto& t = j["targets"][i];
    const std::string where = "targets[" + std::to_string(i) + "]";
    if (!t.is_object()) throw std::invalid_argument(where + " must be an object");
    GazeTarget g;
    g.label = t.contains("label") && t["label"].is_string() ? t["label"].get<std::string>() : std::to_string(i);
    if (!t.contains("target_deg")) throw std::invalid_argument(where + ".target_deg is missing");
    const Eigen::Vector2d td = jsonPoint(t["target_deg"], where + ".target_deg");
    if (std::abs(td[0]) >= 90 || std::abs(td[1]) >= 90)
      throw std::invalid_argument(where + ".target_deg must lie within +-90 deg");
    g.target_deg = {td[0], td[1]};
    if (t.contains("holdout")) {
      if (!t["holdout"].is_boolean()) throw std::invalid_argument(where + ".holdout must be true or false");
      g.holdout = t["holdout"].get<bool>();
    }
    if (!t.contains("pupil_px") || !t["pupil_px"].is_array() || t["pupil_px"].empty())
      throw std::invalid_argument(where + ".pupil_px must be a non-empty array of [x, y]");
    for (std::size_t k = 0; k < t["pupil_px"].size(); ++k)
      g.pupil_px.push_back(jsonPoint(t["pupil_px"][k], where + ".pupil_px[" + std::to_string(k) + "]"));
    out.push_back(std::move(g));
  }
  return out;
}

nlohmann::json gazeSamplesToJson(const std::vector<GazeTarget>& targets) {
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& t : targets) {
    nlohmann::json px = nlohmann::json::array();
    for (const auto& p : t.pupil_px) px.push_back({p[0], p[1]});
    arr.push_back({{"label", t.label},
                   {"target_deg", {t.target_deg[0], t.target_deg[1]}},
                   {"holdout", t.holdout},
                   {"pupil_px", px}});
  }
  return {{"format", "fovea-gaze-samples"}, {"version", 1}, {"targets", arr}};
}

Eigen::Vector2d averagedPupil(const std::vector<Eigen::Vector2d>& s, int count) {
  if (s.empty()) throw std::invalid_argument("no pupil samples to average");
  const std::size_t n = std::min(s.size(), static_cast<std::size_t>(std::max(1, count)));
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (std::size_t i = s.size() - n; i < s.size(); ++i) m += s[i];
  return m / static_cast<double>(n);
}

std::array<double, 2> GazeMap::gazeDeg(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d q = (p - centre_px) / scale_px;
  const Eigen::RowVector2d g = terms(model, q[0], q[1]) * coefficients;
  return {g[0], g[1]};
}

GazeMap fitGazeMap(const std::vector<Eigen::Vector2d>& pupil, const std::vector<std::array<double, 2>>& gaze,
                   GazeModel model) {
  const int k = termCount(model), n = static_cast<int>(pupil.size());
  if (pupil.size() != gaze.size()) throw std::invalid_argument("pupil and gaze lists differ in length");
  if (n < k)
    throw std::invalid_argument(std::string("the ") + modelName(model) + " model has " + std::to_string(k) +
                                " terms and needs at least as many calibration targets; got " + std::to_string(n));
  for (int i = 0; i < n; ++i)
    if (!pupil[i].allFinite() || !std::isfinite(gaze[i][0]) || !std::isfinite(gaze[i][1]))
      throw std::invalid_argument("calibration target " + std::to_string(i) + " holds a non-finite value");
  GazeMap m;
  m.model = model;
  for (const auto& p : pupil) m.centre_px += p;
  m.centre_px /= n;
  double r2 = 0;
  for (const auto& p : pupil) r2 += (p - m.centre_px).squaredNorm();
  m.scale_px = std::sqrt(r2 / n);
  if (!(m.scale_px > 1e-9)) throw std::invalid_argument("all calibration pupil positions coincide");
  Eigen::MatrixXd a(n, k);
  Eigen::MatrixX2d b(n, 2);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d q = (pupil[i] - m.centre_px) / m.scale_px;
    a.row(i) = terms(model, q[0], q[1]);
    b(i, 0) = gaze[i][0];
    b(i, 1) = gaze[i][1];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  qr.setThreshold(1e-9);
  if (qr.rank() < k)
    throw std::invalid_argument(std::string("the calibration pupil positions leave the ") + modelName(model) +
                                " model undetermined (rank " + std::to_string(qr.rank()) + " of " + std::to_string(k) +
                                "): targets repeated, collinear, or too symmetric for its terms");
  m.coefficients = qr.solve(b);
  return m;
}

double angleBetweenDeg(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  // atan2(|a x b|, a.b): accurate for small angles, unlike acos.
  const Eigen::Vector3d u = gazeDirection(a[0], a[1]), v = gazeDirection(b[0], b[1]);
  return radToDeg(std::atan2(u.cross(v).norm(), u.dot(v)));
}

GazeCalibrationResult calibrateGaze(const std::vector<GazeTarget>& targets, const GazeCalibrationOptions& o) {
  std::vector<const GazeTarget*> cal, held;
  for (const auto& t : targets) (t.holdout ? held : cal).push_back(&t);
  GazeCalibrationResult r;
  r.calibration_targets = static_cast<int>(cal.size());
  const GazeModel model = o.model.value_or(defaultModel(r.calibration_targets));
  auto fit = [&](const GazeTarget* skip) {
    std::vector<Eigen::Vector2d> p;
    std::vector<std::array<double, 2>> g;
    for (const GazeTarget* t : cal)
      if (t != skip) {
        p.push_back(averagedPupil(t->pupil_px, o.average));
        g.push_back(t->target_deg);
      }
    return fitGazeMap(p, g, model);
  };
  r.map = fit(nullptr);
  double ss = 0;
  for (const GazeTarget* t : cal)
    ss += std::pow(angleBetweenDeg(t->target_deg, r.map.gazeDeg(averagedPupil(t->pupil_px, o.average))), 2);
  r.fit_rms_deg = std::sqrt(ss / static_cast<double>(cal.size()));

  if (!held.empty()) {
    r.validation = "holdout";
    for (const GazeTarget* t : held) r.validated.push_back(evaluate(r.map, *t, o.average));
  } else {
    r.validation = "leave-one-out";
    for (const GazeTarget* t : cal) {
      GazeMap m;
      try {
        m = fit(t);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("no held-out targets, and leave-one-out cannot refit without target ") +
                                    t->label + ": " + e.what() +
                                    "; mark validation targets with \"holdout\": true or add targets");
      }
      r.validated.push_back(evaluate(m, *t, o.average));
    }
  }
  double s2s = 0, sd = 0;
  for (const auto& v : r.validated) {
    r.accuracy_mean_deg += v.error_deg;
    r.accuracy_max_deg = std::max(r.accuracy_max_deg, v.error_deg);
    s2s += v.precision_rms_s2s_deg * v.precision_rms_s2s_deg;
    sd += v.precision_sd_deg * v.precision_sd_deg;
  }
  const double nv = static_cast<double>(r.validated.size());
  r.accuracy_mean_deg /= nv;
  r.precision_rms_s2s_deg = std::sqrt(s2s / nv);
  r.precision_sd_deg = std::sqrt(sd / nv);
  return r;
}

}  // namespace fovea::gaze
