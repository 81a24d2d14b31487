#!/usr/bin/env bash
# README "run": install Debian packages (idempotent), build the studio and the CLI in the
# default tree (warnings as errors; scripts/test.sh tests the same tree), open fovea-studio on
# the embedded default prototype scene. Without a DISPLAY it runs under Xvfb, saves a
# screenshot of the window, prints its path and exits 0.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
source scripts/ccache-env.sh
cmake --preset default >/dev/null
cmake --build --preset default --target fovea-studio fovea-cli
studio=build/default/app/fovea-studio
if [ -n "${DISPLAY:-}" ]; then
  exec "$studio" "$@"
fi
shot="${FOVEA_SCREENSHOT:-$PWD/build/default/fovea-studio-screenshot.png}"
xvfb-run -a -s "-screen 0 1920x1080x24" "$studio" "$@" --screenshot "$shot" --size 1600x1000 >/dev/null
echo "Screenshot of the studio: $shot"
