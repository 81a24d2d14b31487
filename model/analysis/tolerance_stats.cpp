#include "model/analysis/tolerance_stats.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <string>

namespace fovea {

namespace {

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double variance(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return s / static_cast<double>(v.size() - 1);
}

// Linear-interpolated quantile of sorted data (type 7).
double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const double h = q * static_cast<double>(sorted.size() - 1);
  const std::size_t i = static_cast<std::size_t>(std::floor(h));
  if (i + 1 >= sorted.size()) return sorted.back();
  return sorted[i] + (h - static_cast<double>(i)) * (sorted[i + 1] - sorted[i]);
}

}  // namespace

std::array<double, 2> wilsonInterval(double p, double n, double z) {
  if (!(n > 0)) return {0.0, 1.0};
  const double z2n = z * z / n;
  const double centre = (p + 0.5 * z2n) / (1 + z2n);
  const double half = z / (1 + z2n) * std::sqrt(p * (1 - p) / n + z2n / (4 * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

namespace {

// Mean without overflow: a running mean stays within [min, max] of the data (the sum of two
// numbers near 1e308 is inf).
double runningMean(const std::vector<double>& v) {
  double m = 0;
  for (std::size_t i = 0; i < v.size(); ++i) m += (v[i] - m) / static_cast<double>(i + 1);
  return m;
}

// Where x falls in [lo, hi] as a fraction in [0, 1], computed on halves so that hi - lo cannot
// overflow (lo = -1e308, hi = 1e308).
double fractionIn(double x, double lo, double hi) {
  const double span = 0.5 * hi - 0.5 * lo;
  if (!(span > 0)) return 0.0;
  return std::clamp((0.5 * x - 0.5 * lo) / span, 0.0, 1.0);
}

// Distribution of the finite values of v; non-finite ones (a figure or an input whose spread
// overflowed a double) are counted in "non_finite" and kept out of every statistic and bin.
nlohmann::json distribution(const std::vector<double>& all) {
  std::vector<double> v;
  v.reserve(all.size());
  std::size_t non_finite = 0;
  for (double x : all) {
    if (std::isfinite(x))
      v.push_back(x);
    else
      ++non_finite;
  }
  nlohmann::json j;
  j["count"] = v.size();
  j["non_finite"] = non_finite;
  if (v.empty()) return j;
  std::sort(v.begin(), v.end());
  const double sum_mean = mean(v);  // the plain sum, as before, unless it overflowed
  j["mean"] = std::isfinite(sum_mean) ? sum_mean : runningMean(v);
  j["std"] = std::sqrt(variance(v));
  j["min"] = v.front();
  j["max"] = v.back();
  j["p05"] = quantile(v, 0.05);
  j["p50"] = quantile(v, 0.50);
  j["p95"] = quantile(v, 0.95);
  constexpr int kBins = 20;
  std::vector<int> counts(kBins, 0);
  const double lo = v.front(), hi = v.back();
  for (double x : v) {
    // fractionIn is in [0, 1]: the index is always in 0 .. kBins - 1.
    const int b = std::min(kBins - 1, static_cast<int>(fractionIn(x, lo, hi) * kBins));
    ++counts[static_cast<std::size_t>(b)];
  }
  std::vector<double> edges(kBins + 1);
  // std::lerp: (1 - t) lo + t hi term by term, finite for any finite lo, hi (hi - lo may overflow).
  for (int b = 0; b <= kBins; ++b) edges[b] = b == kBins ? hi : std::lerp(lo, hi, static_cast<double>(b) / kBins);
  j["histogram"] = {{"edges", edges}, {"counts", counts}};
  return j;
}

struct Indices {
  std::vector<double> first, total;
};

Indices estimate(const std::vector<double>& fa, const std::vector<double>& fb,
                 const std::vector<std::vector<double>>& ab, const std::vector<std::size_t>& rows) {
  std::vector<double> all;
  for (std::size_t j : rows) all.push_back(fa[j]), all.push_back(fb[j]);
  const double v = variance(all), f0 = mean(all);
  Indices out;
  if (!(v > 0)) return out;
  const double m = static_cast<double>(rows.size());
  for (const auto& abp : ab) {
    double s1 = 0, st = 0;
    for (std::size_t j : rows) {
      // Saltelli et al. 2010, Table 2 (b), with f(B) centred on the mean (same expectation,
      // far smaller variance when the output's mean is large against its spread, as an FOV's).
      s1 += (fb[j] - f0) * (abp[j] - fa[j]);
      st += (fa[j] - abp[j]) * (fa[j] - abp[j]);  // Jansen 1999, Table 2 (f)
    }
    out.first.push_back(s1 / m / v);
    out.total.push_back(st / (2.0 * m) / v);
  }
  return out;
}

}  // namespace

std::vector<SobolIndex> sobolIndices(const std::vector<double>& fa, const std::vector<double>& fb,
                                     const std::vector<std::vector<double>>& ab, int bootstrap, std::uint64_t seed) {
  const std::size_t m = fa.size();
  std::vector<std::size_t> rows(m);
  std::iota(rows.begin(), rows.end(), std::size_t{0});
  const Indices base = estimate(fa, fb, ab, rows);
  if (base.first.empty()) return {};
  std::vector<SobolIndex> out(ab.size());
  std::vector<std::vector<double>> bf(ab.size()), bt(ab.size());
  for (int b = 0; b < bootstrap; ++b) {
    for (std::size_t j = 0; j < m; ++j)
      rows[j] = std::min(m - 1, static_cast<std::size_t>(counterUniform(seed, b, 7, j) * static_cast<double>(m)));
    const Indices e = estimate(fa, fb, ab, rows);
    if (e.first.empty()) continue;
    for (std::size_t p = 0; p < ab.size(); ++p) bf[p].push_back(e.first[p]), bt[p].push_back(e.total[p]);
  }
  for (std::size_t p = 0; p < ab.size(); ++p) {
    out[p].first = base.first[p];
    out[p].total = base.total[p];
    out[p].first_se = std::sqrt(variance(bf[p]));
    out[p].total_se = std::sqrt(variance(bt[p]));
  }
  return out;
}

nlohmann::json toleranceStatistics(const ToleranceSpec& spec, std::uint64_t seed,
                                   const std::vector<ToleranceRecord>& records) {
  nlohmann::json out;
  const auto& names = toleranceFigureNames();
  const std::size_t k = spec.parameters.size(), n = records.size();
  for (const auto& r : records)
    if (r.inputs.size() != k || r.figures.size() != names.size())
      throw std::invalid_argument("tolerance statistics: trial " + std::to_string(r.trial) + " has " +
                                  std::to_string(r.inputs.size()) + " inputs and " + std::to_string(r.figures.size()) +
                                  " figures, the spec " + std::to_string(k) + " and " + std::to_string(names.size()));
  std::vector<double> fail(n);
  std::size_t passed = 0, invalid = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool ok = tolerancePasses(spec, records[i]);
    fail[i] = ok ? 0.0 : 1.0;
    passed += ok;
    invalid += !records[i].valid;
  }
  // Yield.
  const std::size_t blocks = spec.sobol ? n / (k + 2) : 0;
  const double independent = spec.sobol ? static_cast<double>(std::max<std::size_t>(1, 2 * blocks)) : double(n);
  const double p = n ? static_cast<double>(passed) / static_cast<double>(n) : 0.0;
  // What the interval rests on, for the front ends to print beside the number: with the
  // Saltelli design only the A and B rows of each block are independent draws.
  const std::string basis = spec.sobol ? std::to_string(static_cast<long long>(independent)) +
                                             " independent samples: the A and B rows of the Saltelli design's " +
                                             std::to_string(blocks) + (blocks == 1 ? " block" : " blocks") +
                                             " (its A_B rows repeat their values)"
                                       : std::to_string(n) + " independent samples (plain Monte Carlo)";
  out["yield"] = {{"value", p},
                  {"passed", passed},
                  {"trials", n},
                  {"invalid_units", invalid},
                  {"standard_error", std::sqrt(p * (1 - p) / independent)},
                  {"independent_samples", independent},
                  {"confidence_95", wilsonInterval(p, independent)},
                  {"confidence_method", "Wilson score interval over the independent samples"},
                  {"interval_basis", basis},
                  {"method", spec.sobol ? "pass fraction over all trials; binomial standard error over the A and B "
                                          "rows of the Saltelli design (the A_B rows are correlated with them)"
                                        : "pass fraction; binomial standard error"}};
  // Distributions (valid units).
  nlohmann::json figures = nlohmann::json::object();
  for (std::size_t f = 0; f < names.size(); ++f) {
    std::vector<double> v;
    for (const auto& r : records)
      if (r.valid) v.push_back(r.figures[f]);
    figures[names[f]] = distribution(v);
  }
  out["figures"] = figures;
  nlohmann::json inputs = nlohmann::json::object();
  for (std::size_t q = 0; q < k; ++q) {
    std::vector<double> v;
    v.reserve(records.size());
    for (const auto& r : records) v.push_back(r.inputs[q]);
    inputs[spec.parameters[q].name] = distribution(v);
  }
  out["inputs"] = inputs;
  // Sensitivity.
  nlohmann::json sens;
  if (spec.sobol && blocks >= 2) {
    sens["method"] =
        "Saltelli design (blocks of A, B and A_B^(p) rows); first-order index: Saltelli et al. 2010 estimator; "
        "total index: Jansen 1999 estimator; standard errors: bootstrap over the blocks";
    sens["base_samples"] = blocks;
    sens["bootstrap_resamples"] = spec.bootstrap;
    nlohmann::json outputs = nlohmann::json::object();
    auto indicesOf = [&](const std::function<double(std::size_t)>& y) {
      std::vector<double> fa(blocks), fb(blocks);
      std::vector<std::vector<double>> ab(k, std::vector<double>(blocks));
      for (std::size_t j = 0; j < blocks; ++j) {
        fa[j] = y(j * (k + 2));
        fb[j] = y(j * (k + 2) + 1);
        for (std::size_t q = 0; q < k; ++q) ab[q][j] = y(j * (k + 2) + 2 + q);
      }
      const std::vector<SobolIndex> s = sobolIndices(fa, fb, ab, spec.bootstrap, seed);
      nlohmann::json arr = nlohmann::json::array();
      for (std::size_t q = 0; q < s.size(); ++q)
        arr.push_back({{"parameter", spec.parameters[q].name},
                       {"first_order", s[q].first},
                       {"first_order_se", s[q].first_se},
                       {"total", s[q].total},
                       {"total_se", s[q].total_se}});
      return arr;
    };
    outputs["failure"] = indicesOf([&](std::size_t i) { return fail[i]; });
    for (std::size_t f = 0; f < names.size(); ++f)
      outputs[names[f]] = indicesOf([&](std::size_t i) { return records[i].valid ? records[i].figures[f] : 0.0; });
    sens["outputs"] = outputs;
    // Ranking: by total index on the failure indicator, else on the smallest FOV.
    std::string by = outputs["failure"].empty() ? "fov_min_deg" : "failure";
    nlohmann::json arr = outputs[by];
    std::vector<nlohmann::json> rows(arr.begin(), arr.end());
    std::stable_sort(rows.begin(), rows.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
      // A non-finite or null index (outputs that overflowed) ranks last: NaN would break the
      // strict weak order std::stable_sort needs.
      auto key = [](const nlohmann::json& r) {
        const double t = r["total"].is_number() ? r["total"].get<double>() : -HUGE_VAL;
        return std::isfinite(t) ? t : -HUGE_VAL;
      };
      return key(a) > key(b);
    });
    nlohmann::json ranking = nlohmann::json::array();
    for (const auto& r : rows) ranking.push_back(r["parameter"]);
    sens["ranked_by"] = by;
    sens["ranking"] = ranking;
  } else {
    sens["method"] = spec.sobol ? "too few trials for the Saltelli design (need 2 blocks of parameters + 2)"
                                : "none (plain Monte Carlo)";
  }
  out["sensitivity"] = sens;
  // Inverse.
  nlohmann::json inv;
  inv["target_yield"] = spec.target_yield;
  inv["method"] =
      "one parameter's width scaled by c, the others at spec; yield at c by likelihood-ratio reweighting of the "
      "independent trials (self-normalised; with the Saltelli design its A and B rows); the largest c reaching the "
      "target (c <= 1 bounded, <= 2 normal) while at least 20 effective trials support it";
  nlohmann::json per = nlohmann::json::array();
  for (std::size_t q = 0; q < k; ++q) {
    const ToleranceParameter& t = spec.parameters[q];
    auto yieldAt = [&](double c, double* ess) {
      double sw = 0, sw2 = 0, sp = 0;
      for (std::size_t i = 0; i < n; ++i) {
        // Independent rows only: the A_B rows repeat the A rows' values of all but one parameter.
        if (spec.sobol && (i % (k + 2) >= 2 || i / (k + 2) >= blocks)) continue;
        const double w = t.scaledDensityRatio(records[i].inputs[q], c);
        sw += w;
        sw2 += w * w;
        sp += w * (1.0 - fail[i]);
      }
      if (ess) *ess = sw2 > 0 ? sw * sw / sw2 : 0.0;
      return sw > 0 ? sp / sw : 0.0;
    };
    const double c_max = t.bounded() ? 1.0 : 2.0, c_min = 0.05;
    constexpr int kGrid = 40;
    constexpr double kMinEffective = 20;
    double found = -1;
    // What the scan reached when it found nothing: the best yield, at which scale, and why it stopped.
    double best_yield = -1, best_scale = c_max, last_scale = c_max;
    bool ran_out = false;
    for (int g = 0; g <= kGrid; ++g) {
      const double c = c_max - (c_max - c_min) * g / kGrid;
      double ess = 0;
      const double y = yieldAt(c, &ess);
      if (ess < kMinEffective) {  // too few trials left near the mean to say more
        ran_out = true;
        break;
      }
      last_scale = c;
      if (y > best_yield) best_yield = y, best_scale = c;
      if (y >= spec.target_yield) {
        double good = c, bad = g == 0 ? c : c_max - (c_max - c_min) * (g - 1) / kGrid;
        for (int it = 0; it < 30 && bad > good; ++it) {
          const double mid = 0.5 * (good + bad);
          double e = 0;
          (yieldAt(mid, &e) >= spec.target_yield && e >= kMinEffective ? good : bad) = mid;
        }
        found = good;
        break;
      }
    }
    nlohmann::json row{{"parameter", t.name}, {"spec_width", t.width()}};
    if (found > 0) {
      double ess = 0;
      row["achievable"] = true;
      row["scale"] = found;
      row["width"] = found * t.width();
      row["yield"] = yieldAt(found, &ess);
      row["effective_samples"] = ess;
      row["at_scan_limit"] = found >= c_max;
    } else {
      // Tightening this one alone does not reach the target (down to 5 % of its width, or
      // until fewer than 20 effective trials remain).
      row["achievable"] = false;
      if (best_yield >= 0) {
        row["best_yield"] = best_yield;
        row["best_scale"] = best_scale;
        row["smallest_scale"] = last_scale;
      }
      row["stopped_by"] = ran_out ? (best_yield < 0 ? "effective_samples_at_spec" : "effective_samples") : "scan_limit";
    }
    per.push_back(row);
  }
  inv["parameters"] = per;
  out["inverse"] = inv;
  return out;
}

}  // namespace fovea
