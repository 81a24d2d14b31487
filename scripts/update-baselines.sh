#!/usr/bin/env bash
# Regenerates the image baselines of the 3D view, the retina view and the grating-vector
# cloud (tests/baselines/*.png) from the current code: builds the baseline test and runs it
# under Xvfb with FOVEA_UPDATE_BASELINES=1. Look at the PNGs before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ccache-env.sh
cmake --preset default >/dev/null
cmake --build --preset default --target gui_tst_view_baselines
# Through CTest: it gives the test its paths (FOVEA_SOURCE_DIR, FOVEA_TEST_TMP: tests/CMakeLists.txt).
FOVEA_UPDATE_BASELINES=1 xvfb-run -a -s "-screen 0 1920x1080x24" \
  ctest --test-dir build/default -R '^gui[.]tst_view_baselines$' --output-on-failure
git status --short tests/baselines
