#include "app/cli/eye_option.h"

#include "app/cli/cli_common.h"

namespace fovea::cli {

std::shared_ptr<std::string> addEyeOption(CLI::App* cmd) {
  auto eye = std::make_shared<std::string>();
  cmd->add_option("--eye", *eye,
                  "eye of a binocular scene: left, right or both (default: both for a binocular scene; a "
                  "monocular scene has no --eye)")
      ->check(CLI::IsMember({"left", "right", "both"}));
  return eye;
}

std::vector<EyeRun> eyeRuns(const Scene& scene, const std::string& eye, const std::string& scene_name) {
  if (!scene.binocular) {
    if (!eye.empty())
      usageError("--eye " + eye + ": " + (scene_name.empty() ? std::string("the embedded scene") : scene_name) +
                 " is a monocular scene (no \"binocular\" block): it has one eye; leave out --eye");
    return {EyeRun{std::nullopt, scene}};
  }
  std::vector<EyeRun> runs;
  for (const EyeSide side : {EyeSide::Left, EyeSide::Right})
    if (eye.empty() || eye == "both" || eye == eyeSideName(side)) runs.push_back({side, eyeScene(scene, side)});
  return runs;
}

nlohmann::json combineEyeDocuments(const std::vector<EyeRun>& runs, const std::vector<nlohmann::json>& docs) {
  if (runs.size() == 1) {
    nlohmann::json out = docs.front();
    if (runs.front().side) out["eye"] = eyeSideName(*runs.front().side);
    return out;
  }
  nlohmann::json eyes = nlohmann::json::object();
  nlohmann::json out;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    eyes[eyeSideName(*runs[i].side)] = docs[i];
    if (*runs[i].side == EyeSide::Right) out = docs[i];
  }
  out["eyes"] = std::move(eyes);
  return out;
}

std::string eyePrefix(const EyeRun& run) {
  return run.side ? std::string(eyeSideName(*run.side)) + " eye: " : std::string();
}

}  // namespace fovea::cli
