// fovea-cli tolerance SCENE --spec TOL.json --trials N --seed S [--shard K/N] --json: Monte Carlo
// tolerancing of the design (docs/tolerancing.md): yield against the spec's pass criterion,
// the distribution of every figure, variance-based sensitivity indices and the inverse.
// --slurm DIR writes a Slurm job array (one shard per task) and its merge step; --submit runs
// it with sbatch, follows it with squeue/sacct and merges the parts. --eye left|right|both: each
// eye of a binocular scene (app/cli/eye_option.h; a shard or a Slurm job runs one eye).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "app/cli/slurm_job.h"
#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"
#include "model/io/json_input.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {

namespace cmd_tolerance {  // one per command file: fovea-cli compiles in unity batches
namespace {

struct Args {
  std::string scene, spec, shard, slurm_dir, tasks, eye;
  unsigned long long trials = 100, seed = 1;
  int threads = 0, shards = 4, poll_seconds = 2, timeout_seconds = 3600;
  bool json = false, submit = false;
};

ToleranceSpec loadSpec(const std::string& path) {
  nlohmann::json j;
  try {
    j = readJsonFile(path);
  } catch (const std::exception& e) {
    inputError(std::string("--spec ") + e.what());
  }
  try {
    return parseToleranceSpec(j, path);  // "PATH: json.path: problem"
  } catch (const std::invalid_argument& e) {
    inputError(e.what());
  }
}

std::string absolute(const std::string& p) {
  return p.empty() ? p : std::filesystem::absolute(p).lexically_normal().string();
}

std::string selfExecutable() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) inputError("--slurm: cannot find the fovea-cli executable");
  return std::string(buf, static_cast<std::size_t>(n));
}

// Submits the array (or the listed tasks), follows it until no task is queued or running,
// then merges. Returns the merged result.
nlohmann::json submitAndFollow(const SlurmJob& job, const Args& a) {
  std::vector<std::string> sbatch{"sbatch", "--parsable"};
  if (!a.tasks.empty()) sbatch.push_back("--array=" + a.tasks);
  sbatch.push_back(sbatchPath(job));
  const CommandResult sub = runCommand(sbatch);
  if (sub.status != 0) inputError("--submit: sbatch failed (is Slurm installed and running?)");
  std::string id = sub.out.substr(0, sub.out.find_first_of(";\n"));
  std::cerr << "tolerance: submitted job array " << id << " (" << job.shards << " shards) from " << sbatchPath(job)
            << "\n";
  const auto start = std::chrono::steady_clock::now();
  int last_done = -1;
  for (;;) {
    const CommandResult q = runCommand({"squeue", "-h", "-r", "-j", id, "-o", "%i %T"});
    int queued = 0;
    std::istringstream lines(q.out);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) ++queued;
    const int done = job.shards - static_cast<int>(missingParts(job).size());
    if (done != last_done || queued == 0) {
      std::cerr << "tolerance: " << done << "/" << job.shards << " parts written, " << queued
                << " task(s) queued or running\n";
      last_done = done;
    }
    if (q.status == 0 && queued == 0) break;
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(a.timeout_seconds))
      inputError("--submit: job " + id + " still running after --timeout-seconds; parts are in " + job.dir);
    std::this_thread::sleep_for(std::chrono::seconds(a.poll_seconds));
  }
  // Final states from the accounting (when the cluster keeps it) for the report.
  const CommandResult acct = runCommand({"sacct", "-n", "-P", "-X", "-j", id, "-o", "JobID,State,ExitCode"});
  if (acct.status == 0 && !acct.out.empty()) std::cerr << "tolerance: sacct:\n" << acct.out;
  const std::vector<int> missing = missingParts(job);
  if (!missing.empty()) {
    std::string list;
    for (int k : missing) list += (list.empty() ? "" : ",") + std::to_string(k);
    inputError("--submit: task(s) " + list + " of job " + id + " failed (no complete part; logs " + job.dir +
               "/task-K.log); re-run them alone with: fovea-cli tolerance ... --slurm " + job.dir +
               " --submit --tasks " + list + "  (or sbatch --array=" + list + " " + sbatchPath(job) + ")");
  }
  const CommandResult merged = runCommand({"sh", mergePath(job)});
  if (merged.status != 0) inputError("--submit: the merge step failed (" + mergePath(job) + ")");
  return readJsonFile(resultPath(job));
}

void printSummary(const nlohmann::json& r) {
  const auto& y = r["yield"];
  std::cout << "yield " << y["value"].get<double>() * 100 << " % (" << y["passed"] << "/" << y["trials"]
            << ", standard error " << y["standard_error"].get<double>() * 100 << " %)\n";
  // The interval and what it rests on (fewer independent samples than trials with the Saltelli design).
  if (y.contains("confidence_95") && y["confidence_95"].size() == 2) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "95 %% interval %.1f - %.1f %%", y["confidence_95"][0].get<double>() * 100,
                  y["confidence_95"][1].get<double>() * 100);
    const std::string basis =
        y.contains("interval_basis") && y["interval_basis"].is_string()
            ? y["interval_basis"].get<std::string>()
            : std::to_string(static_cast<long long>(y.value("independent_samples", 0.0))) + " independent samples";
    std::cout << buf << " over " << basis << "\n";
  }
  for (const auto& [name, d] : r["figures"].items())
    if (d.contains("mean"))
      std::cout << name << ": mean " << d["mean"] << ", p05 " << d["p05"] << ", p95 " << d["p95"] << "\n";
  if (r["sensitivity"].contains("ranking")) {
    std::cout << "drives " << r["sensitivity"]["ranked_by"].get<std::string>() << ":";
    for (const auto& p : r["sensitivity"]["ranking"]) std::cout << " " << p.get<std::string>();
    std::cout << "\n";
  }
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("tolerance", "Monte Carlo tolerancing: yield, figure distributions, sensitivity");
  auto a = std::make_shared<Args>();
  cmd->add_option("SCENE", a->scene, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--spec", a->spec, "tolerance spec (JSON, docs/tolerancing.md)")->required();
  cmd->add_option("--trials", a->trials, "number of trials (default 100)")->check(CLI::Range(1ULL, 10000000ULL));
  addSeedOption(cmd, a->seed,
                "random seed (default 1, an integer in [0, 2^64 - 1]); trial i depends only on (seed, i)");
  cmd->add_option("--shard", a->shard, "run only shard K/N (0-based) and print its part for `fovea-cli merge`");
  cmd->add_option("--threads", a->threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--slurm", a->slurm_dir, "write a Slurm job array (one shard per task) and merge step to DIR");
  cmd->add_option("--shards", a->shards, "with --slurm: number of array tasks (default 4)")
      ->check(CLI::Range(1, 10000));
  cmd->add_flag("--submit", a->submit, "with --slurm: sbatch it, follow it, merge the parts when it completes");
  cmd->add_option("--tasks", a->tasks, "with --submit: only these array tasks (e.g. 1,3: re-run failed ones)");
  cmd->add_option("--poll-seconds", a->poll_seconds, "with --submit: squeue interval (default 2)")
      ->check(CLI::Range(1, 600));
  cmd->add_option("--timeout-seconds", a->timeout_seconds, "with --submit: give up after (default 3600)")
      ->check(CLI::Range(1, 10000000));
  cmd->add_flag("--json", a->json, "print JSON");
  const auto eye = addEyeOption(cmd);
  cmd->callback([a, eye] {
    a->eye = *eye;
    if (!a->tasks.empty() && a->tasks.find_first_not_of("0123456789,-") != std::string::npos)
      usageError("--tasks: expected a list like 1,3 or 0-2");
    if (a->submit && a->slurm_dir.empty()) usageError("--submit needs --slurm DIR");
    const ToleranceSpec spec = loadSpec(a->spec);
    const std::vector<EyeRun> runs = eyeRuns(loadSceneOrExit(a->scene), a->eye, a->scene);
    if (runs.size() != 1 && !a->shard.empty())
      usageError("--shard: a shard runs one eye of a binocular scene: give --eye left or right");
    if (runs.size() != 1 && !a->slurm_dir.empty())
      usageError("--slurm: a job runs one eye of a binocular scene: give --eye left or right");
    for (const EyeRun& run : runs) {
      try {
        checkToleranceSpecPaths(spec, run.scene, a->spec);
      } catch (const std::invalid_argument& e) {
        inputError(eyePrefix(run) + e.what());
      }
    }
    if (!a->slurm_dir.empty()) {
      if (!a->shard.empty()) usageError("--shard and --slurm exclude each other (each array task runs a shard)");
      SlurmJob job;
      job.dir = absolute(a->slurm_dir);
      job.executable = selfExecutable();
      job.scene = absolute(a->scene);
      job.spec = absolute(a->spec);
      job.trials = a->trials;
      job.seed = a->seed;
      job.shards = a->shards;
      job.eye = a->eye;
      try {
        writeSlurmJob(job);
      } catch (const std::exception& e) {
        inputError(std::string("--slurm: ") + e.what());
      }
      if (!a->submit) {
        std::cout << "wrote " << sbatchPath(job) << " and " << mergePath(job) << "\nsubmit: sbatch " << sbatchPath(job)
                  << "; then: sh " << mergePath(job) << "\n";
        return;
      }
      const nlohmann::json r = submitAndFollow(job, *a);
      if (a->json)
        printJson(r);
      else
        printSummary(r);
      return;
    }
    std::optional<tbb::global_control> limit;
    if (a->threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, a->threads);
    int k = 0, n = 1;
    if (!a->shard.empty()) std::tie(k, n) = parseShard(a->shard);
    std::vector<nlohmann::json> docs;
    for (const EyeRun& run : runs) {
      const Scene& scene = run.scene;
      ToleranceRunInfo info;
      info.scene_name = scene.name;
      info.scene_digest = sceneDigest(scene);
      info.seed = a->seed;
      info.trials = a->trials;
      try {
        info.nominal = nominalFigures(scene, spec);
      } catch (const std::invalid_argument& e) {
        inputError("tolerance: the nominal scene: " + eyePrefix(run) + e.what());
      }
      Progress progress("tolerance");
      StudyControl control;
      control.on_progress = [&progress](double f) { progress.update(f); };
      const auto trials = runToleranceTrials(scene, spec, a->seed, shardRange(a->trials, k, n), control);
      if (!trials.ok()) inputError("tolerance did not complete");
      if (!a->shard.empty()) {
        const nlohmann::json part = tolerancePartJson(spec, info, k, n, *trials.value);
        if (a->json)
          printJson(part, /*compact=*/true);
        else
          std::cout << "shard " << k << "/" << n << ": " << trials.value->size()
                    << " trials (use --json for the part)\n";
        return;
      }
      docs.push_back(toleranceResultJson(spec, info, *trials.value));
    }
    if (a->json) return printJson(combineEyeDocuments(runs, docs));
    for (std::size_t i = 0; i < runs.size(); ++i) {
      if (runs[i].side) std::cout << eyePrefix(runs[i]) << "\n";
      printSummary(docs[i]);
    }
  });
}

const Registrar reg{"tolerance", &install};

}  // namespace
}  // namespace cmd_tolerance
}  // namespace fovea::cli
