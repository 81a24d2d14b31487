#!/usr/bin/env bash
# Lint step of the test command (scripts/test.sh), also runnable alone after a build:
#   bash scripts/lint.sh [--all [--record]] [BUILD_DIR]
#                                         (default build/default; needs its compile_commands.json)
# 1. clang-format --dry-run -Werror over every tracked C++ file (the repo's .clang-format);
# 2. clang-tidy (the repo's .clang-tidy, findings are errors) over the translation units of
#    $FOVEA_TIDY_DIRS (default: model; findings fatal unless FOVEA_TIDY_STRICT=0), one per core.
#    By default only the files changed since a base commit (the merge base with the upstream
#    branch, else the last recorded full clean pass in scripts/tidy-clean-commit; $FOVEA_TIDY_BASE
#    overrides): on a cold machine a full pass costs ~35 min on two cores, the changed files
#    seconds to minutes. --all checks every unit (before a release; .ci/weekly); --all --record
#    writes HEAD to scripts/tidy-clean-commit when that pass is clean and the tree is committed.
#    Units whose inputs are unchanged since a clean check are skipped either way
#    (scripts/tidy_cached.py; cache in ~/.cache/fovea-clang-tidy or $FOVEA_TIDY_CACHE).
#    FOVEA_TIDY_DIRS="model devices app/cli" widens it.
# FOVEA_LINT=format or FOVEA_LINT=tidy runs one half only. Exit status 1 on any finding.
set -euo pipefail
cd "$(dirname "$0")/.."
tidy_all=()
record=0
while [ $# -gt 0 ]; do
  case "$1" in
    --all) tidy_all=(--all); shift ;;
    --record) record=1; shift ;;
    -*) echo "lint: unknown option $1 (use --all, --record)" >&2; exit 2 ;;
    *) break ;;
  esac
done
if [ $record = 1 ] && [ ${#tidy_all[@]} = 0 ]; then
  echo "lint: --record needs --all (only a full pass is recorded)" >&2; exit 2
fi
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
  if ! python3 scripts/tidy_cached.py --build "$build" --jobs "$(nproc)" "${tidy_all[@]}" ${FOVEA_TIDY_DIRS:-model}; then
    if [ "${FOVEA_TIDY_STRICT:-1}" = 1 ]; then
      status=1
    else
      echo "lint: clang-tidy findings above are advisory (FOVEA_TIDY_STRICT=0)"
    fi
  elif [ $record = 1 ]; then
    if [ -z "$(git status --porcelain -- ${FOVEA_TIDY_DIRS:-model} .clang-tidy)" ]; then
      git rev-parse HEAD > scripts/tidy-clean-commit
      echo "lint: recorded $(cut -c1-10 scripts/tidy-clean-commit) as the last full clean pass (commit scripts/tidy-clean-commit)"
    else
      echo "lint: not recorded: uncommitted changes below ${FOVEA_TIDY_DIRS:-model}"
    fi
  fi
fi
exit $status
