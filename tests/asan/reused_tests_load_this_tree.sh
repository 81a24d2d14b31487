#!/usr/bin/env bash
# The ASan tree runs the default tree's model, devices and fuzz test executables against its
# own libraries (tests/CMakeLists.txt, FOVEA_TEST_DRIVERS). This check fails unless every
# reused executable, in the environment CTest gives it (LD_LIBRARY_PATH, LD_PRELOAD), maps
# each REQUIRED file (this tree's libfovea_model.so, the ASan runtime) and maps every
# libfovea_*.so it needs from one of the ALLOWED folders (this tree's library folders).
#   reused_tests_load_this_tree.sh REQUIRED[,REQUIRED...] ALLOWED_DIR[,ALLOWED_DIR...] EXECUTABLE...
set -euo pipefail
IFS=, read -r -a required <<<"$1"
IFS=, read -r -a allowed <<<"$2"
shift 2
[ $# -gt 0 ] || { echo "no executable given" >&2; exit 2; }
required_real=()
for r in "${required[@]}"; do required_real+=("$(readlink -f "$r")"); done
allowed_real=()
for d in "${allowed[@]}"; do allowed_real+=("$(readlink -f "$d")"); done
# Each test is a link to its batch's executable (tests/CMakeLists.txt): every executable once,
# by its real path (the loader maps the same libraries whichever link starts it).
mapfile -t executables < <(for e in "$@"; do readlink -f "$e"; done | sort -u)
status=0
for exe in "${executables[@]}"; do
  # The dynamic loader's own list of what it maps (ldd's mechanism: main is not run).
  if ! maps=$(LD_TRACE_LOADED_OBJECTS=1 "$exe" 2>&1); then
    echo "FAIL $exe: the loader could not list its libraries: $maps"; status=1; continue
  fi
  mapfile -t resolved < <(sed -n 's/.*=> \(\/[^ ]*\) (0x.*/\1/p; s/^[[:space:]]*\(\/[^ ]*\) (0x.*/\1/p' <<<"$maps" |
                          xargs -r readlink -f)
  for want in "${required_real[@]}"; do
    if ! printf '%s\n' "${resolved[@]}" | grep -qxF "$want"; then
      echo "FAIL $exe does not map $want"; status=1
    fi
  done
  for got in "${resolved[@]}"; do
    case "$got" in
      */libfovea_*.so)
        ok=0
        for d in "${allowed_real[@]}"; do [ "$(dirname "$got")" = "$d" ] && ok=1; done
        if [ $ok = 0 ]; then echo "FAIL $exe maps $got, from outside this tree's library folders"; status=1; fi ;;
    esac
  done
done
[ $status = 0 ] && echo "all ${#executables[@]} reused executables ($# tests) map ${required[*]}, and libfovea_*.so only from ${allowed[*]}"
exit $status
