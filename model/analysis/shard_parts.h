#pragma once
// The bookkeeping every merge of sharded runs shares (tolerance_run.h, sweep_shards.h): each
// part is a `format` document of one run (the `same` keys equal part 1's), names its shard
// [K, N] with one N for all, and every shard 0..N-1 comes exactly once. Throws
// std::invalid_argument naming the part and the problem ("merge: part 3: shard 1 given twice",
// "merge: missing shard(s) 2 of 3").

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fovea {

// How messages name part i: "merge: FILE" when the files are known, else "merge: part N".
inline std::string shardPartName(const std::vector<std::string>& sources, std::size_t i) {
  return "merge: " + (i < sources.size() ? sources[i] : "part " + std::to_string(i + 1));
}

// Shard K -> index of its part.
inline std::map<int, std::size_t> indexShardParts(const std::vector<nlohmann::json>& parts, const std::string& format,
                                                  const std::vector<std::string>& same, const std::string& run,
                                                  const std::vector<std::string>& sources = {}) {
  if (parts.empty()) throw std::invalid_argument("merge: no parts given");
  int shards = -1;
  std::map<int, std::size_t> seen;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const nlohmann::json& p = parts[i];
    const std::string where = shardPartName(sources, i);
    if (!p.is_object() || p.value("format", std::string()) != format)
      throw std::invalid_argument(std::string(where).append(": not a ").append(format).append(" document"));
    for (const std::string& k : same)
      if (!p.contains(k) || p[k] != parts[0][k]) {
        throw std::invalid_argument(std::string(where)
                                        .append(": \"")
                                        .append(k)
                                        .append("\" differs from part 1 (not the same ")
                                        .append(run)
                                        .append(")"));
      }
    // "shard": [K, N], integers with 0 <= K < N <= 100000 (the CLI's --shard range).
    std::vector<int> sh;
    if (p.contains("shard") && p["shard"].is_array() && p["shard"].size() == 2)
      for (const auto& v : p["shard"])
        if (v.is_number_integer() && v.get<std::int64_t>() >= 0 && v.get<std::int64_t>() <= 100000)
          sh.push_back(v.get<int>());
    if (sh.size() != 2 || sh[0] >= sh[1])
      throw std::invalid_argument(where + ": shard: must be [K, N], integers with 0 <= K < N <= 100000");
    if (shards < 0) shards = sh[1];
    if (sh[1] != shards) throw std::invalid_argument(where + ": shard count differs from part 1");
    if (seen.count(sh[0])) throw std::invalid_argument(where + ": shard " + std::to_string(sh[0]) + " given twice");
    seen[sh[0]] = i;
  }
  std::string missing;
  for (int k = 0; k < shards; ++k)
    if (!seen.count(k)) missing += (missing.empty() ? "" : ",") + std::to_string(k);
  if (!missing.empty())
    throw std::invalid_argument("merge: missing shard(s) " + missing + " of " + std::to_string(shards));
  return seen;
}

}  // namespace fovea
