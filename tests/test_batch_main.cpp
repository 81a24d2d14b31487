// The main of every test executable (tests/test_batch.h): runs the one registered test named
// by argv[0]'s file name (the test's link, as CTest starts it) or by argv[1] (the batch started
// directly: `tests/model_tests_2 model_tst_fit [Qt Test arguments]`).
#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include "model/memory_policy.h"
#include "tests/test_batch.h"

namespace fovea::testing {
namespace {

std::map<std::string, TestMain>& registry() {
  static std::map<std::string, TestMain> tests;  // filled by static initialisers, before main
  return tests;
}

std::string current;

std::string fileName(const char* path) {
  const char* slash = std::strrchr(path, '/');
  return slash == nullptr ? path : slash + 1;
}

}  // namespace

bool registerTest(const char* name, TestMain main) {
  registry().emplace(name, main);
  return true;
}

const char* currentTestName() {
  return current.c_str();
}

}  // namespace fovea::testing

int main(int argc, char** argv) {
  using namespace fovea::testing;
  fovea::keepFreedMemoryForReuse();  // as the executables run (model/memory_policy.h)
  const auto& tests = registry();
  if (argc >= 1) {
    if (const auto it = tests.find(fileName(argv[0])); it != tests.end()) {
      current = it->first;
      return it->second(argc, argv);
    }
  }
  if (argc >= 2) {
    if (const auto it = tests.find(argv[1]); it != tests.end()) {
      current = it->first;
      // The test sees its own name as its program name, then its arguments.
      return it->second(argc - 1, argv + 1);
    }
  }
  std::fprintf(
      stderr,
      "%s holds several tests: run one by its link (tests/<name>) or as `%s <name> [Qt Test arguments]`; names:\n",
      argc >= 1 ? argv[0] : "this test executable", argc >= 1 ? argv[0] : "it");
  for (const auto& [name, main] : tests) std::fprintf(stderr, "  %s\n", name.c_str());
  return 2;
}
