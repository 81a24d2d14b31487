#!/usr/bin/env bash
# Lint step of the test command (scripts/test.sh), also runnable alone after a build:
#   bash scripts/lint.sh [--all] [--record] [BUILD_DIR]
#                                         (default build/default; needs its compile_commands.json)
# 1. clang-format --dry-run -Werror over every tracked C++ file (the repo's .clang-format);
# 2. clang-tidy (the repo's .clang-tidy, findings are errors) over the translation units of
#    $FOVEA_TIDY_DIRS (default: model; findings fatal unless FOVEA_TIDY_STRICT=0), one per core.
#    By default only the files changed since a base commit (the merge base with the upstream
#    branch, else the last recorded clean pass in scripts/tidy-clean-commit; $FOVEA_TIDY_BASE
#    overrides): on a cold machine a full pass costs ~35 min on two cores, the changed files
#    seconds to minutes. --all checks every unit (before a release; .ci/weekly). --record writes
#    HEAD to scripts/tidy-clean-commit when the pass proves every unit clean and the tree is
#    committed: with --all, or alone (then every unit that reads a file changed since the
#    recorded commit is checked: a unit's result depends only on its inputs; tidy_cached.py).
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
record_args=()
if [ $record = 1 ]; then
  if [ -n "$(git status --porcelain -- ${FOVEA_TIDY_DIRS:-model} .clang-tidy)" ]; then
    echo "lint: --record needs the tree below ${FOVEA_TIDY_DIRS:-model} committed" >&2; exit 2
  fi
  record_args=(--record scripts/tidy-clean-commit)
  if [ ${#tidy_all[@]} = 0 ]; then record_args+=(--dependents); fi
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
  if ! python3 scripts/tidy_cached.py --build "$build" --jobs "$(nproc)" "${tidy_all[@]}" \
      "${record_args[@]}" ${FOVEA_TIDY_DIRS:-model}; then
    if [ "${FOVEA_TIDY_STRICT:-1}" = 1 ]; then
      status=1
    else
      echo "lint: clang-tidy findings above are advisory (FOVEA_TIDY_STRICT=0)"
    fi
  fi
fi
exit $status
