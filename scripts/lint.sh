#!/usr/bin/env bash
# Lint step of the test command (scripts/test.sh), also runnable alone after a build:
#   bash scripts/lint.sh [BUILD_DIR]      (default build/default; needs its compile_commands.json)
# 1. clang-format --dry-run -Werror over every tracked C++ file (the repo's .clang-format);
# 2. clang-tidy (the repo's .clang-tidy, findings are errors) over the translation units of
#    $FOVEA_TIDY_DIRS (default: model; findings fatal unless FOVEA_TIDY_STRICT=0), one per core, skipping units whose inputs are unchanged
#    since a clean check (scripts/tidy_cached.py; cache in ~/.cache/fovea-clang-tidy or
#    $FOVEA_TIDY_CACHE). FOVEA_TIDY_DIRS="model devices app/cli" widens it.
# FOVEA_LINT=format or FOVEA_LINT=tidy runs one half only. Exit status 1 on any finding.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/default}"
what="${FOVEA_LINT:-all}"
status=0

if [ "$what" != tidy ]; then
  mapfile -t files < <(git ls-files '*.cpp' '*.h')
  bad=$(clang-format --dry-run "${files[@]}" 2>&1 | grep -E '^[^ ]+:[0-9]+:[0-9]+: (warning|error):' | cut -d: -f1 | sort -u || true)
  if [ -n "$bad" ]; then
    echo "lint: clang-format: $(echo "$bad" | wc -l) of ${#files[@]} files are not formatted (fix: clang-format -i FILE):"
    echo "$bad" | sed 's/^/  /'
    status=1
  else
    echo "lint: clang-format: all ${#files[@]} files formatted"
  fi
fi

if [ "$what" != format ]; then
  if [ ! -f "$build/compile_commands.json" ]; then
    echo "lint: $build/compile_commands.json missing: configure and build first (cmake --preset default)" >&2
    exit 1
  fi
  # shellcheck disable=SC2086  # a list of folders
  # Findings are fatal (model/ had a complete clean pass); FOVEA_TIDY_STRICT=0 prints them only.
  if ! python3 scripts/tidy_cached.py --build "$build" --jobs "$(nproc)" ${FOVEA_TIDY_DIRS:-model}; then
    if [ "${FOVEA_TIDY_STRICT:-1}" = 1 ]; then
      status=1
    else
      echo "lint: clang-tidy findings above are advisory (FOVEA_TIDY_STRICT=0)"
    fi
  fi
fi
exit $status
