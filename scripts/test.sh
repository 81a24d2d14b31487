#!/usr/bin/env bash
# README "test": install Debian packages (idempotent), build the default tree (warnings as
# errors; the same tree scripts/run.sh uses), run the whole CTest suite (GUI tests under
# Xvfb), lint (scripts/lint.sh: clang-format and clang-tidy), then build the ASan + UBSan tree
# and run the model/devices/CLI tests in it. Two trees in all: build/default and build/asan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
source scripts/ccache-env.sh
start=$(date +%s)
# Configure, build, test (CMakePresets.json workflow "default").
xvfb-run -a -s "-screen 0 1920x1080x24" cmake --workflow --preset default
echo "== Lint =="
bash scripts/lint.sh build/default
echo "== ASan + UBSan configuration =="
cmake --workflow --preset asan
echo "test.sh: all suites and the lint passed in $(( $(date +%s) - start )) s"
