// fovea-cli fit SCENE --targets TARGETS.json --free PATHS... [--targets-select SEL] [--starts N] [--seed S]
// [--max-evals N]
//   [--write-scene OUT.json] --json: fits scene numbers to target observables (docs/fitting.md).
// The options are those of the registry's "fit" analysis (model/analysis/fit_analysis.cpp),
// written by hand because --free takes several values (each may also hold several specs
// separated by spaces, as the studio's "Copy CLI" writes them). --eye left|right|both: each eye
// of a binocular scene (app/cli/eye_option.h); --write-scene only with --eye right (the fitted
// numbers are the scene's own train; the left train is its mirror image).
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "app/cli/study_cli.h"
#include "model/analysis/fit_analysis.h"
#include "model/io/save_temporaries.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace cmd_fit {  // one per command file: fovea-cli compiles in unity batches
namespace {

struct Args {
  std::string scene, targets, write_scene, targets_select;
  std::vector<std::string> free;
  int starts = 3, seed = 1, max_evals = 0;
  bool json = false;
};

// A number of the document for people: 6 significant digits, "-" for null.
std::string shown(const nlohmann::json& v) {
  if (!v.is_number()) return "-";
  std::ostringstream o;
  o << std::setprecision(6) << v.get<double>();
  return o.str();
}

void printTable(const nlohmann::json& r) {
  std::cout << "chi2 " << shown(r["chi2_initial"]) << " -> " << shown(r["chi2"]) << " (" << r["dof"] << " dof, "
            << r["evaluations"] << " evaluations), reduced chi2 " << shown(r["reduced_chi2"]) << "\n";
  if (r.contains("targets_select") && !r["targets_select"].get<std::string>().empty())
    std::cout << "targets: " << r["targets"].size() << " of " << r["targets_available"] << " ("
              << r["targets_select"].get<std::string>() << ")\n";
  // chi2/dof > 1: the scaled uncertainties are the ones to quote (the JSON keeps both).
  const bool scaled = r.value("uncertainties_shown", std::string()) == "scaled";
  for (const auto& p : r["parameters"])
    std::cout << "  " << p["path"].get<std::string>() << " = " << shown(p["fitted"]) << " +- "
              << shown(p[scaled ? "uncertainty_scaled" : "uncertainty"]) << " " << p["unit"].get<std::string>()
              << (scaled ? " (scaled by sqrt(chi2/dof); unscaled +- " + shown(p["uncertainty"]) + ")" : std::string())
              << " (was " << shown(p["initial"]) << ")\n";
  for (const auto& t : r["targets"])
    std::cout << "  " << t["id"].get<std::string>() << ": model " << shown(t["model"]) << ", value "
              << shown(t["value"]) << " +- " << shown(t["sigma"]) << " " << t["unit"].get<std::string>() << " ("
              << shown(t["normalised"]) << " sigma)\n";
  for (const auto& w : r["warnings"]) {
    const std::string who = w["parameter"].get<std::string>();
    std::cerr << "warning: " << (who.empty() ? "" : who + ": ") << w["message"].get<std::string>() << "\n";
  }
}

void install(CLI::App& app) {
  const analysis::AnalysisDefinition& def = *analysis::findAnalysisDefinition("fit");
  auto* cmd = app.add_subcommand("fit", def.title + ": " + def.description);
  auto a = std::make_shared<Args>();
  cmd->add_option("SCENE", a->scene, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--targets", a->targets, "targets file (JSON, docs/fitting.md)")->required();
  cmd->add_option("--free", a->free, "scene paths to fit: PATH, PATH=LO:HI or PATH=+-D (one or more)")
      ->required()
      ->expected(1, -1);
  cmd->add_option("--targets-select", a->targets_select, def.parameter("targets-select")->help);
  cmd->add_option("--starts", a->starts, def.parameter("starts")->help);
  cmd->add_option("--seed", a->seed, def.parameter("seed")->help);
  cmd->add_option("--max-evals", a->max_evals, def.parameter("max-evals")->help);
  auto* write_scene = cmd->add_option("--write-scene", a->write_scene, "write the fitted scene to this file");
  cmd->add_flag("--json", a->json, "print the fit document (JSON)");
  const auto eye = addEyeOption(cmd);
  cmd->callback([a, &def, write_scene, eye] {
    std::string free;
    for (const auto& f : a->free) free += (free.empty() ? "" : " ") + f;
    nlohmann::json values{
        {"targets", a->targets},
        {"free", free},
        {"targets-select", a->targets_select.empty() ? nlohmann::json() : nlohmann::json(a->targets_select)},
        {"starts", a->starts},
        {"seed", a->seed},
        {"max-evals", a->max_evals}};
    for (const auto& p : analysis::validateValues(def, values)) usageError(p.text("--"));
    const Scene scene = loadSceneOrExit(a->scene);
    const std::vector<EyeRun> runs = eyeRuns(scene, *eye, a->scene);
    checkOutputOption(write_scene, a->write_scene);
    if (!a->write_scene.empty() && (runs.size() != 1 || runs.front().side == EyeSide::Left))
      usageError(
          "--write-scene: the fitted numbers of a binocular scene are written for the scene's own (right) train: "
          "give --eye right (the left train is its mirror image)");
    std::vector<nlohmann::json> docs;
    docs.reserve(runs.size());
    for (const EyeRun& run : runs) docs.push_back(runStudy(def, run.scene, values));
    if (!a->write_scene.empty()) {
      try {
        // The right eye's paths are the scene's own: its block is kept.
        saveSceneFileAtomic(analysis::sceneWithFittedValues(scene, docs.front()), a->write_scene);
      } catch (const std::exception& e) {
        inputError("--write-scene: " + std::string(e.what()));
      }
    }
    if (a->json) return printJson(combineEyeDocuments(runs, docs));
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (runs[i].side) std::cout << eyePrefix(runs[i]) << "\n";
      printTable(docs[i]);
    }
  });
}

const Registrar reg{"fit", &install};

}  // namespace
}  // namespace cmd_fit
}  // namespace fovea::cli
