#pragma once
// Running a design study: many independent samples (gaze angles, parameter values, lens
// candidates) computed in parallel on all cores, with progress, cancellation and a cache.
//
// Determinism: every sample is computed by a pure function of its index and written to its
// own slot, so the result is bit-for-bit the same whatever the thread count or scheduling.
// Cancellation: checked before each sample starts; a cancelled study returns
// StudyStatus::Cancelled and NO value (never a partial result labelled final).

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>
// Qt's `emit` keyword macro breaks oneTBB headers: hide it while they are read, so this
// header can be included after Qt's (GUI, Qt Test).
#ifdef emit
#pragma push_macro("emit")
#undef emit
#define FOVEA_RESTORE_QT_EMIT
#endif
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#ifdef FOVEA_RESTORE_QT_EMIT
#pragma pop_macro("emit")
#undef FOVEA_RESTORE_QT_EMIT
#endif

namespace fovea {

enum class StudyStatus { Completed, Cancelled };

// How the caller follows and stops a study. Both members are optional.
struct StudyControl {
  // Fraction done in [0, 1]; called with a lock held (never concurrently), from any thread.
  std::function<void(double)> on_progress;
  // Set to true (from any thread) to stop: running samples finish, no new one starts.
  const std::atomic<bool>* cancel = nullptr;

  bool cancelled() const { return cancel != nullptr && cancel->load(std::memory_order_relaxed); }
};

template <class T>
struct StudyOutcome {
  StudyStatus status = StudyStatus::Cancelled;
  std::optional<T> value;  // set iff status == Completed
  bool ok() const { return status == StudyStatus::Completed && value.has_value(); }
};

// Reports progress of `total` units from many threads through one StudyControl.
class ProgressCounter {
 public:
  ProgressCounter(const StudyControl& control, std::size_t total) : control_(control), total_(total) {}
  void add(std::size_t units = 1) {
    const std::size_t done = done_.fetch_add(units) + units;
    if (!control_.on_progress || total_ == 0) return;
    std::lock_guard lock(mutex_);
    control_.on_progress(std::min(1.0, static_cast<double>(done) / static_cast<double>(total_)));
  }

 private:
  const StudyControl& control_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
};

// Computes compute(i) for i in [0, n) in parallel (grain 1: samples are expensive) and
// returns them in index order, or Cancelled. `compute` must be thread-safe and pure.
template <class T, class Compute>
StudyOutcome<std::vector<T>> runSamples(std::size_t n, Compute&& compute, const StudyControl& control) {
  StudyOutcome<std::vector<T>> out;
  if (control.cancelled()) return out;
  std::vector<std::optional<T>> results(n);
  ProgressCounter progress(control, n);
  std::atomic<bool> stopped{false};
  tbb::task_group_context context;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          if (control.cancelled()) {
            stopped = true;
            context.cancel_group_execution();
            return;
          }
          results[i].emplace(compute(i));
          progress.add();
        }
      },
      tbb::simple_partitioner(), context);
  if (stopped || control.cancelled()) return out;
  std::vector<T> values;
  values.reserve(n);
  for (auto& s : results) {
    if (!s) return out;  // a sample skipped by cancellation: never report partial results
    values.push_back(std::move(*s));
  }
  out.status = StudyStatus::Completed;
  out.value = std::move(values);
  return out;
}

// 64-bit FNV-1a of a text: the cache key digest (the full key text is kept and compared,
// so a digest collision can never return a wrong result).
std::uint64_t fnv1a64(std::string_view text);
std::string hexDigest(std::string_view text);

// Results of finished studies keyed by "<study>\n<parameters>\n<serialized scene>": the
// same scene content and parameters give the stored result without recomputation. Kept in
// memory; with a directory set, also as <digest>.json files so separate processes (the
// CLI) reuse them. Thread-safe. Only completed results are ever stored.
class StudyCache {
 public:
  static StudyCache& global();

  static std::string makeKey(std::string_view study, const nlohmann::json& parameters, std::string_view scene_text);

  std::optional<nlohmann::json> find(const std::string& key);
  void store(const std::string& key, const nlohmann::json& result);
  void setDirectory(std::string directory);  // empty: memory only
  void clear();
  std::size_t hits() const { return hits_; }
  std::size_t misses() const { return misses_; }

 private:
  std::mutex mutex_;
  std::unordered_map<std::string, nlohmann::json> memory_;
  std::string directory_;
  std::atomic<std::size_t> hits_{0}, misses_{0};
};

}  // namespace fovea
