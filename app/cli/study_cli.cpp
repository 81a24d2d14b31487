#include "app/cli/study_cli.h"

#include <sys/stat.h>

#include <cstdlib>
#include <stdexcept>

#include "app/cli/cli_common.h"
#include "model/analysis/study_runner.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {

void addNoCacheFlag(CLI::App* cmd, bool& no_cache) {
  cmd->add_flag("--no-cache", no_cache, "recompute even when an identical study is cached");
}

nlohmann::json runStudy(const analysis::AnalysisDefinition& def, const Scene& scene, const nlohmann::json& values) {
  Progress progress(def.id);
  StudyControl control;
  control.on_progress = [&progress](double f) { progress.update(f); };
  std::optional<nlohmann::json> out;
  try {
    out = def.run(scene, values, control);
  } catch (const std::invalid_argument& e) {
    usageError(std::string("--") + e.what());
  } catch (const std::runtime_error& e) {
    inputError(e.what());
  }
  if (!out) inputError(def.id + " did not complete");
  return *out;
}

namespace {
std::string cacheDirectory() {
  if (const char* d = std::getenv("FOVEA_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/fovea-studio/studies";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/fovea-studio/studies";
  return {};
}

std::string executableStamp() {
  struct stat st {};
  if (::stat("/proc/self/exe", &st) != 0) return "unknown";
  return std::to_string(st.st_size) + ":" + std::to_string(st.st_mtim.tv_sec) + "." +
         std::to_string(st.st_mtim.tv_nsec);
}
}  // namespace

nlohmann::json cachedStudy(const std::string& study, const nlohmann::json& parameters, const Scene& scene,
                           bool no_cache, const std::function<nlohmann::json()>& compute) {
  StudyCache& cache = StudyCache::global();
  cache.setDirectory(cacheDirectory());
  nlohmann::json keyed = parameters;
  keyed["executable"] = executableStamp();
  const std::string key = StudyCache::makeKey(study, keyed, serializeScene(scene));
  if (!no_cache) {
    if (auto hit = cache.find(key)) {
      (*hit)["cached"] = true;
      return *hit;
    }
  }
  nlohmann::json result = compute();
  cache.store(key, result);
  result["cached"] = false;
  return result;
}

}  // namespace fovea::cli
