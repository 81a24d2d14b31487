#include "app/cli/slurm_job.h"

#include "model/io/json_input.h"
#include "model/io/output_file.h"

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace fovea::cli {

namespace {

std::string quote(const std::string& s) {  // POSIX shell single quotes
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void writeFile(const std::string& path, const std::string& text, bool executable) {
  writeOutputFile(path, text);  // checked, fsync'ed, atomic: a full disk leaves no empty script
  if (executable)
    std::filesystem::permissions(path, std::filesystem::perms::owner_exec | std::filesystem::perms::group_exec,
                                 std::filesystem::perm_options::add);
}

}  // namespace

std::string partPath(const SlurmJob& job, int shard) {
  return job.dir + "/part-" + std::to_string(shard) + ".json";
}
std::string sbatchPath(const SlurmJob& job) {
  return job.dir + "/tolerance.sbatch";
}
std::string mergePath(const SlurmJob& job) {
  return job.dir + "/merge.sh";
}
std::string resultPath(const SlurmJob& job) {
  return job.dir + "/result.json";
}

void writeSlurmJob(const SlurmJob& job) {
  std::filesystem::create_directories(job.dir);
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "# fovea-cli tolerance as a Slurm job array: array task K runs shard K/" << job.shards
    << " and writes part-K.json;\n"
    << "# re-run failed tasks alone with: sbatch --array=K[,K...] " << sbatchPath(job) << "\n"
    << "#SBATCH --job-name=fovea-tolerance\n"
    << "#SBATCH --array=0-" << job.shards - 1 << "\n"
    << "#SBATCH --cpus-per-task=" << job.threads_per_task << "\n"
    << "#SBATCH --output=" << job.dir << "/task-%a.log\n"
    << "set -e\n"
    << "K=\"$SLURM_ARRAY_TASK_ID\"\n"
    << quote(job.executable) << " tolerance " << (job.scene.empty() ? "" : quote(job.scene) + " ") << "--spec "
    << quote(job.spec) << (job.eye.empty() ? std::string() : " --eye " + job.eye) << " --trials " << job.trials
    << " --seed " << job.seed << " --shard \"$K/" << job.shards << "\" --threads " << job.threads_per_task
    << " --json > " << quote(job.dir) << "/part-\"$K\".json.tmp\n"
    << "mv " << quote(job.dir) << "/part-\"$K\".json.tmp " << quote(job.dir) << "/part-\"$K\".json\n";
  writeFile(sbatchPath(job), s.str(), true);
  std::ostringstream m;
  m << "#!/bin/sh\n# Merges the parts of the tolerance job array into result.json.\nset -e\n"
    << quote(job.executable) << " merge";
  for (int k = 0; k < job.shards; ++k) m << " " << quote(partPath(job, k));
  m << " --json > " << quote(resultPath(job)) << ".tmp\nmv " << quote(resultPath(job)) << ".tmp "
    << quote(resultPath(job)) << "\n";
  writeFile(mergePath(job), m.str(), true);
}

CommandResult runCommand(const std::vector<std::string>& argv) {
  std::string cmd;
  for (const auto& a : argv) cmd += (cmd.empty() ? "" : " ") + quote(a);
  cmd += " 2>/dev/null";
  CommandResult r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::vector<int> missingParts(const SlurmJob& job) {
  std::vector<int> out;
  for (int k = 0; k < job.shards; ++k) {
    std::ifstream f(partPath(job, k));
    bool ok = false;
    if (f) {
      try {
        const nlohmann::json j = readJsonFile(partPath(job, k));
        ok = j.value("format", std::string()) == "fovea-tolerance-part";
      } catch (const std::exception&) {
        ok = false;
      }
    }
    if (!ok) out.push_back(k);
  }
  return out;
}

}  // namespace fovea::cli
