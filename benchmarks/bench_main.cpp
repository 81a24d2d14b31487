// The benchmarks' main: Google Benchmark's, after the process's allocator policy
// (model/memory_policy.h), as fovea-cli and fovea-studio run.
#include <benchmark/benchmark.h>

#include "model/memory_policy.h"

int main(int argc, char** argv) {
  fovea::keepFreedMemoryForReuse();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
