#include "model/analysis/study_runner.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/io/json_input.h"
#include "model/scene/scene_io.h"

namespace fovea {

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::string hexDigest(std::string_view text) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(fnv1a64(text)));
  return buf;
}

StudyCache& StudyCache::global() {
  static StudyCache cache;
  return cache;
}

std::string StudyCache::makeKey(std::string_view study, const nlohmann::json& parameters, std::string_view scene_text) {
  std::string key(study);
  key += '\n';
  key += parameters.dump();
  key += '\n';
  key += scene_text;
  return key;
}

std::optional<nlohmann::json> StudyCache::find(const std::string& key) {
  std::lock_guard lock(mutex_);
  if (auto it = memory_.find(key); it != memory_.end()) {
    ++hits_;
    return it->second;
  }
  if (!directory_.empty()) {
    // Through the JSON input limits: a damaged or hostile cache file is a miss (rewritten by store()).
    auto text = readInputFile(std::filesystem::path(directory_) / (hexDigest(key) + ".json"));
    if (auto* bytes = std::get_if<0>(&text)) {
      auto parsed = parseJsonText(*bytes);
      if (auto* stored = std::get_if<nlohmann::json>(&parsed); stored && stored->is_object() &&
                                                               stored->contains("result") && stored->contains("key") &&
                                                               (*stored)["key"] == key) {
        memory_[key] = (*stored)["result"];
        ++hits_;
        return (*stored)["result"];
      }
    }
  }
  ++misses_;
  return std::nullopt;
}

void StudyCache::store(const std::string& key, const nlohmann::json& result) {
  std::lock_guard lock(mutex_);
  memory_[key] = result;
  if (directory_.empty()) return;
  try {
    std::filesystem::create_directories(directory_);
    const nlohmann::json stored{{"key", key}, {"result", result}};
    writeFileAtomic(std::filesystem::path(directory_) / (hexDigest(key) + ".json"), stored.dump());
  } catch (const std::exception&) {
    // The disk cache is an optimisation: a read-only or full disk only costs recomputation.
  }
}

void StudyCache::setDirectory(std::string directory) {
  std::lock_guard lock(mutex_);
  directory_ = std::move(directory);
}

void StudyCache::clear() {
  std::lock_guard lock(mutex_);
  memory_.clear();
  hits_ = 0;
  misses_ = 0;
}

}  // namespace fovea
