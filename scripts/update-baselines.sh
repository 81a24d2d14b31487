#!/usr/bin/env bash
# Regenerates the image baselines of the 3D view, the retina view and the grating-vector
# cloud (tests/baselines/*.png) from the current code: builds the baseline test and runs it
# under Xvfb with FOVEA_UPDATE_BASELINES=1. Look at the PNGs before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
cmake --preset default >/dev/null
cmake --build --preset default --target gui_tst_view_baselines
FOVEA_UPDATE_BASELINES=1 FOVEA_TEST_TMP="$PWD/build/default/tests/tmp" \
  xvfb-run -a -s "-screen 0 1920x1080x24" build/default/tests/gui_tst_view_baselines
git status --short tests/baselines
