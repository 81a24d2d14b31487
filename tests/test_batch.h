#pragma once
// Test executables hold several tests each (issue 25): tests/CMakeLists.txt compiles the
// tst_*.cpp files of an area in batches, one executable a batch, so that the json, Eigen and
// Qt Test templates every test instantiates are compiled once per batch. Each tst_*.cpp keeps
// its own main (QTEST_MAIN and friends, or its own): the batch's generated source renames it
// and registers it here under the test's name. A test runs alone, as before: CTest runs the
// link named after it (tests/<area>_<name>, a symbolic link to its batch), and the batch's main
// (test_batch_main.cpp) picks the test by the name it was started as, or by its first argument.

namespace fovea::testing {

using TestMain = int (*)(int argc, char** argv);

// Registers <main> under <name> (e.g. "model_tst_fit"); called by the batch's generated source.
bool registerTest(const char* name, TestMain main);

// The name of the test this process runs ("model_tst_fit").
const char* currentTestName();

}  // namespace fovea::testing
