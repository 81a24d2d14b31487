#pragma once
// The statistics of a tolerance study from its trial records (the methods are described in
// tolerance_run.h and docs/tolerancing.md): yield, figure distributions, variance-based
// sensitivity indices with bootstrap errors, and the inverse (tolerance per parameter for the
// target yield).

#include <array>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"

namespace fovea {

// "yield", "figures", "sensitivity", "inverse" of the result document.
nlohmann::json toleranceStatistics(const ToleranceSpec& spec, std::uint64_t seed,
                                   const std::vector<ToleranceRecord>& records);

// Wilson score interval of a binomial proportion p over n samples at z standard deviations
// (z = 1.96: 95 %; Wilson 1927, J. Am. Stat. Assoc. 22:209; inside [0, 1] and not empty at
// p = 0 or 1, unlike p +- z SE). {lo, hi}; {0, 1} for n <= 0.
std::array<double, 2> wilsonInterval(double p, double n, double z = 1.96);

struct SobolIndex {
  double first = 0, total = 0, first_se = 0, total_se = 0;
};
// Saltelli 2010 first-order and Jansen 1999 total indices from the outputs of the A rows, the
// B rows and the A_B^(p) rows (ab[p][j]), with bootstrap standard errors (resamples of the
// blocks j drawn from `seed`). Empty if the outputs do not vary.
std::vector<SobolIndex> sobolIndices(const std::vector<double>& fa, const std::vector<double>& fb,
                                     const std::vector<std::vector<double>>& ab, int bootstrap, std::uint64_t seed);

}  // namespace fovea
