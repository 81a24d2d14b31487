#!/usr/bin/env bash
# README "test": install Debian packages (idempotent; those only the tests need while the default
# tree builds), build the default tree (warnings as
# errors; the same tree scripts/run.sh uses), run the whole CTest suite (GUI tests under
# Xvfb), lint (scripts/lint.sh: clang-format and clang-tidy), then build the ASan + UBSan tree
# and run the model/devices/CLI tests in it. Two trees in all: build/default and build/asan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh build
# The packages only the tests and the lint need install while the default tree builds
# (scripts/install-deps.sh); the tests wait for them.
deps_log=$(mktemp)
bash scripts/install-deps.sh test >"$deps_log" 2>&1 &
deps_pid=$!
# Never leave dpkg running behind a failed build: wait for it (killing it would break the install).
trap 'wait "$deps_pid" 2>/dev/null || true; rm -f "$deps_log"' EXIT
source scripts/ccache-env.sh
start=$(date +%s)
# Configure, build, test (the steps of CMakePresets.json's workflow "default").
cmake --preset default
cmake --build --preset default
if ! wait "$deps_pid"; then
  echo "test.sh: installing the test packages failed:" >&2
  cat "$deps_log" >&2
  exit 1
fi
cat "$deps_log"
xvfb-run -a -s "-screen 0 1920x1080x24" ctest --preset default
echo "== Lint =="
bash scripts/lint.sh build/default
echo "== ASan + UBSan configuration =="
cmake --workflow --preset asan
echo "test.sh: all suites and the lint passed in $(( $(date +%s) - start )) s"
