#pragma once
// Where a test finds the source tree and the fovea-cli binary: CTest passes both at run time
// (tests/CMakeLists.txt, ENVIRONMENT) instead of compiling them in as -D string literals, so
// a test's compile command holds no absolute path and ccache reuses its object file in every
// clone and worktree (issue 25; docs/platform.md, "Timings").
#include <cstdio>
#include <cstdlib>

namespace fovea::testing {

// $name, or exit 2 with a message naming it (a test run outside CTest without it set).
inline const char* requiredTestPath(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') {
    std::fprintf(stderr, "%s is not set: run the test through ctest, or set it to the %s\n", name,
                 name[6] == 'S' ? "source tree (the folder holding resources/)" : "fovea-cli binary");
    std::exit(2);
  }
  return value;
}

}  // namespace fovea::testing

#define FOVEA_SOURCE_DIR (::fovea::testing::requiredTestPath("FOVEA_SOURCE_DIR"))
#define FOVEA_CLI_PATH (::fovea::testing::requiredTestPath("FOVEA_CLI_PATH"))
