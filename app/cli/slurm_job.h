#pragma once
// A tolerance study as a Slurm job array (one shard per array task) plus its merge step, and
// following a submitted array with squeue/sacct until its parts can be merged.

#include <string>
#include <vector>

namespace fovea::cli {

struct SlurmJob {
  std::string dir;         // absolute: scripts, parts, logs and the merged result go here
  std::string executable;  // absolute path of fovea-cli
  std::string scene;       // absolute path, or empty for the embedded scene
  std::string spec;        // absolute path
  std::string eye;         // --eye of every task (one eye of a binocular scene), or empty
  unsigned long long trials = 0, seed = 0;
  int shards = 4;
  int threads_per_task = 1;
};

std::string partPath(const SlurmJob& job, int shard);
std::string sbatchPath(const SlurmJob& job);  // DIR/tolerance.sbatch
std::string mergePath(const SlurmJob& job);   // DIR/merge.sh
std::string resultPath(const SlurmJob& job);  // DIR/result.json

// Writes DIR/tolerance.sbatch (array 0..shards-1) and DIR/merge.sh; throws std::runtime_error.
void writeSlurmJob(const SlurmJob& job);

// Runs a command (no shell: arguments are quoted), returns its exit status and stdout.
struct CommandResult {
  int status = -1;
  std::string out;
};
CommandResult runCommand(const std::vector<std::string>& argv);

// Shards whose part file is missing or not a complete part document.
std::vector<int> missingParts(const SlurmJob& job);

}  // namespace fovea::cli
