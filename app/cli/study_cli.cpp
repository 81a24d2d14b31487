#include "app/cli/study_cli.h"

#include <sys/stat.h>

#include <cstdlib>

#include "app/cli/cli_common.h"
#include "model/analysis/study_runner.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {

void addStudyOptions(CLI::App* cmd, StudyCliOptions& options) {
  cmd->add_option("--rays", options.rays, "rays per wavelength per trace (default 12000)")
      ->check(CLI::Range(50, 1000000));
  cmd->add_option("--tolerance-deg", options.tolerance_deg,
                  "eye-box criterion: FOV within this of the zero-gaze FOV (default 3 deg)")
      ->check(CLI::Range(0.0, 90.0));
  cmd->add_option("--fov-method", options.fov_method,
                  "edges (FOV edges root-found to 0.005 deg, default) or dense (counted on the --rays grid)")
      ->check(CLI::IsMember({"edges", "dense"}));
  cmd->add_flag("--no-cache", options.no_cache, "recompute even when an identical study is cached");
}

FovEvaluator studyEvaluator(const StudyCliOptions& options) {
  TraceEvaluatorOptions t;
  t.rays = options.rays;
  t.fov_method = parseFovMethod(options.fov_method).value_or(FovMethod::Edges);
  return traceEvaluator(t);
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
                           const StudyCliOptions& options, const std::function<nlohmann::json()>& compute) {
  StudyCache& cache = StudyCache::global();
  cache.setDirectory(cacheDirectory());
  nlohmann::json keyed = parameters;
  keyed["rays"] = options.rays;
  keyed["tolerance_deg"] = options.tolerance_deg;
  keyed["fov_method"] = options.fov_method;
  keyed["executable"] = executableStamp();
  const std::string key = StudyCache::makeKey(study, keyed, serializeScene(scene));
  if (!options.no_cache) {
    if (auto hit = cache.find(key)) {
      (*hit)["cached"] = true;
      return *hit;
    }
  }
  nlohmann::json result = compute();
  result["fov_method"] = options.fov_method;
  cache.store(key, result);
  result["cached"] = false;
  return result;
}

}  // namespace fovea::cli
