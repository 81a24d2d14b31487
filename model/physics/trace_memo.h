#pragma once
// The memo machinery of the trace pipeline (trace_pipeline.h): stage keys and result tables.
// Each stage's result is stored under a 64-bit hash of exactly the inputs it reads, so a run
// recomputes only the stages whose inputs changed. Internal to model/physics.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "model/scene/scene.h"

namespace fovea::detail {

// 64-bit hash of a sequence of values (splitmix64 finaliser chained: S. Vigna, "An experimental
// exploration of Marsaglia's xorshift generators", ACM TOMS 42 (2016)); -0 and +0 hash alike.
class Hasher {
 public:
  explicit Hasher(const char* tag) { add(std::string(tag)); }
  Hasher& add(std::uint64_t v) {
    h_ = mix(h_ ^ v);
    return *this;
  }
  Hasher& add(double v) {
    if (v == 0.0) v = 0.0;
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return add(bits);
  }
  Hasher& add(int v) { return add(static_cast<std::uint64_t>(static_cast<std::int64_t>(v))); }
  Hasher& add(bool v) { return add(static_cast<std::uint64_t>(v ? 0x5bd1e995u : 0x1b873593u)); }
  Hasher& add(const std::string& s) {
    add(static_cast<std::uint64_t>(s.size()));
    for (std::size_t i = 0; i < s.size(); i += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
      add(w);
    }
    return *this;
  }
  template <class T, std::size_t N>
  Hasher& add(const std::array<T, N>& a) {
    for (const T& v : a) add(v);
    return *this;
  }
  Hasher& add(const Pose& p) { return add(p.position_mm).add(p.rotation_deg); }
  std::uint64_t value() const { return h_; }

 private:
  static std::uint64_t mix(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t h_ = 0x243f6a8885a308d3ULL;
};

// Memo table of one stage type: results by key, least recently used evicted beyond the
// entries of the current run plus `kKeepOld` older ones.
template <class D>
class Memo {
 public:
  std::shared_ptr<D> find(std::uint64_t key, std::uint64_t run) {
    auto it = map_.find(key);
    if (it == map_.end()) return nullptr;
    it->second.last_used = run;
    return it->second.data;
  }
  void put(std::uint64_t key, std::shared_ptr<D> d, std::uint64_t run) { map_[key] = {std::move(d), run}; }
  void evict(std::uint64_t run) {
    constexpr std::size_t kKeepOld = 6;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> old;  // last_used, key
    for (const auto& [k, e] : map_)
      if (e.last_used != run) old.emplace_back(e.last_used, k);
    if (old.size() <= kKeepOld) return;
    std::sort(old.begin(), old.end());
    for (std::size_t i = 0; i + kKeepOld < old.size(); ++i) map_.erase(old[i].second);
  }
  void clear() { map_.clear(); }

 private:
  struct Entry {
    std::shared_ptr<D> data;
    std::uint64_t last_used = 0;
  };
  std::unordered_map<std::uint64_t, Entry> map_;
};

// The one result of a stage that keeps only its latest run (pupil, FOV, analyses).
template <class D>
struct Single {
  std::uint64_t key = 0;
  bool valid = false;
  D data;
  bool holds(std::uint64_t k) const { return valid && key == k; }
  void store(std::uint64_t k) {
    key = k;
    valid = true;
  }
};

}  // namespace fovea::detail
