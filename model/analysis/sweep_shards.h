#pragma once
// A gaze sweep (the "sweep" analysis, gaze_studies.h) run in slices: shard K of N computes the
// optimal shift at the gazes [K G / N, (K + 1) G / N) of the G gazes (shard 0 also at zero gaze,
// the eye box's reference), and writes them at full precision with the run's header (the
// validated values, the scene itself and its digest) to a "fovea-sweep-part" document.
// mergeSweepParts() checks that the parts belong to one run and cover every gaze once, then
// finishes the sweep exactly as one unsharded run does (the eye-box borders bisected on the
// scene carried by the parts): the same document as `fovea-cli sweep --json`, byte for byte.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/study_runner.h"
#include "model/scene/scene.h"

namespace fovea::analysis {

// `values`: the sweep analysis' validated values. Nothing when cancelled. Throws
// std::invalid_argument for a bad shard (0 <= k < n) or gaze range.
std::optional<nlohmann::json> sweepPartJson(const Scene& scene, const nlohmann::json& values, int shard, int shards,
                                            const StudyControl& control = {});

// The sweep document of the parts (any order; "cached" is not set). Throws
// std::invalid_argument naming what does not fit (another run, a missing or repeated shard, an
// incomplete part, a gaze_count or a sample's gaze the values do not give) as
// "merge: SOURCE: json.path: problem" (`sources`: the parts' files; else "part N").
// Nothing when cancelled.
std::optional<nlohmann::json> mergeSweepParts(const std::vector<nlohmann::json>& parts,
                                              const StudyControl& control = {},
                                              const std::vector<std::string>& sources = {});

}  // namespace fovea::analysis
