#!/usr/bin/env bash
# README "test": install Debian packages (idempotent), build (warnings as errors), run the
# whole CTest suite (GUI tests under Xvfb), then the model/devices/CLI tests under
# ASan + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
export CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/fovea-ccache}"
# Relative paths in the cache key: a fresh clone elsewhere reuses earlier compilations.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true CCACHE_MAXSIZE=5G
start=$(date +%s)
cmake --preset ci >/dev/null
cmake --build --preset ci
xvfb-run -a -s "-screen 0 1920x1080x24" ctest --preset ci
echo "== ASan + UBSan configuration =="
cmake --preset asan >/dev/null
cmake --build --preset asan
ctest --preset asan
echo "test.sh: all suites passed in $(( $(date +%s) - start )) s"
