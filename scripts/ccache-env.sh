# Sourced by run.sh, test.sh and update-baselines.sh from the repository root: one ccache
# setting for every build of the project.
#  - CCACHE_BASEDIR + NOHASHDIR: relative paths in the cache key, so a fresh clone elsewhere
#    reuses earlier compilations (the compile commands hold no absolute path: issue 25);
#  - CCACHE_SLOPPINESS: the per-target precompiled headers (cmake/FoveaBuildSpeed.cmake) are
#    cacheable only when ccache ignores the .gch's fresh mtime/ctime and its __DATE__-free
#    defines (ccache manual, "Precompiled headers").
export CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/fovea-ccache}"
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-5G}"
export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
