#pragma once
// Running a tolerance study (tolerance_spec.h, tolerance_trial.h) in slices and reducing it:
//  - trial i depends only on (seed, i), so a shard K/N runs trials [K T / N, (K + 1) T / N)
//    and writes its records to a part document;
//  - the result (yield, figure distributions, sensitivity indices, inverse) is a pure
//    function of the records in trial order: mergeToleranceParts() of all the parts gives
//    the document toleranceResultJson() gives for one unsharded run, byte for byte.
// Statistics (docs/tolerancing.md):
//  - yield: fraction of trials passing every bound of the spec; a trial whose perturbed scene
//    breaks the scene rules fails. Standard error sqrt(p (1 - p) / n) over the independent
//    rows (with the Saltelli design: the A and B rows, 2 per block);
//  - sensitivity (Saltelli design): first-order indices by Saltelli et al. 2010 (Comput. Phys.
//    Commun. 181, 259, Table 2 (b)), total indices by Jansen 1999 (ibid. (f)), for the failure
//    indicator and each figure, with bootstrap standard errors over the blocks;
//  - inverse: per parameter, the largest scale c of its width (sigma or half width; the others
//    at spec) whose yield reaches target_yield, the yield at c estimated from the same trials by
//    likelihood-ratio reweighting (self-normalised importance sampling); c <= 1 for bounded
//    distributions (no samples beyond their support), <= 2 for normal ones; the effective
//    sample size (Kish) is reported with it.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/study_runner.h"
#include "model/analysis/tolerance_spec.h"
#include "model/scene/scene.h"

namespace fovea {

struct ToleranceRecord {
  std::uint64_t trial = 0;
  std::vector<double> inputs, figures;
  bool valid = true;  // false: the perturbed scene broke the scene rules (error says why)
  std::string error;
};

struct TrialRange {
  std::uint64_t begin = 0, end = 0;
};
// Shard k of n (0-based) of `trials`. Throws std::invalid_argument unless 0 <= k < n.
TrialRange shardRange(std::uint64_t trials, int k, int n);

// The nominal unit's figures (every input 0: no offset) and the trials of
// the range, in parallel (cancellable).
std::vector<double> nominalFigures(const Scene& scene, const ToleranceSpec& spec);
StudyOutcome<std::vector<ToleranceRecord>> runToleranceTrials(const Scene& scene, const ToleranceSpec& spec,
                                                              std::uint64_t seed, TrialRange range,
                                                              const StudyControl& control = {});

bool tolerancePasses(const ToleranceSpec& spec, const ToleranceRecord& r);

struct ToleranceRunInfo {
  std::string scene_name, scene_digest;
  std::uint64_t seed = 0, trials = 0;
  std::vector<double> nominal;
};
std::string sceneDigest(const Scene& scene);  // 64-bit FNV-1a of the serialised scene, hex

nlohmann::json tolerancePartJson(const ToleranceSpec& spec, const ToleranceRunInfo& info, int shard, int shards,
                                 const std::vector<ToleranceRecord>& records);
// records: every trial 0..trials-1 in order.
nlohmann::json toleranceResultJson(const ToleranceSpec& spec, const ToleranceRunInfo& info,
                                   const std::vector<ToleranceRecord>& records);
// The CLI's cap of --trials, also the cap of a part's "trials".
inline constexpr std::uint64_t kMaxToleranceTrials = 10000000;

// Throws std::invalid_argument naming what does not fit (different runs, missing or repeated
// shards or trials, records whose inputs/figures do not have the spec's shape) as
// "SOURCE: json.path: problem", SOURCE the part's file (`sources`, one per part) or "part N".
nlohmann::json mergeToleranceParts(const std::vector<nlohmann::json>& parts,
                                   const std::vector<std::string>& sources = {});

}  // namespace fovea
