#!/usr/bin/env bash
# Trains the learned pupil detector's two stages (scripts/train_pupil_net.py) and writes
# resources/pupil/pupil-net.onnx (the whole frame at 96 px) and pupil-refine.onnx (a 96 px
# window of the frame at 200 px around the first stage's centre), each with a .json of its
# validation figures. Not part of the test command: the shipped models are what the tests
# check. Deterministic by seed (renderer seeds 1 for training, 7 for validation; PyTorch seed
# 31). The shipped models: the full-frame stage 18000 frames, 24 epochs on one thread in 35
# minutes; the refining stage 72000 frames (those with a pupil less than 60 % visible shown three
# times an epoch), 8 epochs in about 45 minutes; rendering a few
# minutes on two cores when nothing else runs (13 when builds ran beside it). One thread each:
# two intra-op threads on a shared two-core machine stall at their barriers (up to 17 min an
# epoch while builds ran). The trainer stops at --max-minutes whatever the epoch; the .json
# files give the epochs it ran.
#   scripts/train-pupil-net.sh [--stage full|refine|both] [--frames N] [--epochs E]
#       [--refine-frames N] [--refine-epochs E] [--max-minutes M] [--work DIR]
# FOVEA_CLI overrides the fovea-cli to use (default: build/default/app/fovea-cli, built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES=18000 EPOCHS=24 MINUTES=65 WORK=/tmp/fovea-pupil-train STAGE=both RFRAMES=72000 REPOCHS=8
while [[ $# -gt 0 ]]; do
  case "$1" in
    --stage) STAGE=$2; shift 2 ;;
    --refine-frames) RFRAMES=$2; shift 2 ;;
    --refine-epochs) REPOCHS=$2; shift 2 ;;
    --frames) FRAMES=$2; shift 2 ;;
    --epochs) EPOCHS=$2; shift 2 ;;
    --work) WORK=$2; shift 2 ;;
    --max-minutes) MINUTES=$2; shift 2 ;;
    *) echo "train-pupil-net.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
case "$STAGE" in full|refine|both) ;; *) echo "train-pupil-net.sh: --stage $STAGE: full, refine or both" >&2; exit 2 ;; esac
# PyTorch from Debian (the system interpreter: a pyenv or venv python3 does not see it).
if ! /usr/bin/python3 -c "import torch, onnx" 2>/dev/null; then
  sudo=""; [[ $(id -u) -ne 0 ]] && sudo=sudo
  $sudo apt-get install -y python3-torch python3-onnx || { $sudo apt-get update && $sudo apt-get install -y python3-torch python3-onnx; }
fi
CLI=${FOVEA_CLI:-build/default/app/fovea-cli}
if [[ ! -x $CLI ]]; then cmake --preset default && cmake --build --preset default --target fovea-cli; fi
mkdir -p "$WORK"
render() {  # DIR START COUNT SEED [SIZE]
  local size=${5:-96}
  if [[ -f $1/dataset.json ]] && grep -q "\"frames\": $3," "$1/dataset.json" && grep -q "\"start\": $2," "$1/dataset.json" && grep -q "\"seed\": $4," "$1/dataset.json" && tr -d ' \n' < "$1/dataset.json" | grep -q "\"stored_size_px\":\[$size,"; then return; fi
  nice -n 10 "$CLI" eye-dataset --out "$1" --start "$2" --frames "$3" --seed "$4" --size "$size" --no-png
}
train() {  # STAGE OUT EPOCHS DIR... (the last DIR is the validation set)
  local stage=$1 out=$2 epochs=$3; shift 3
  local args=() n=$#
  for ((k = 1; k < n; k++)); do args+=(--data "${!k}"); done
  nice -n 10 /usr/bin/python3 scripts/train_pupil_net.py --stage "$stage" "${args[@]}" --val "${!n}" --out "$out" \
    --epochs "$epochs" --max-minutes "$MINUTES" --threads 1 --occluded-repeats "${OCCLUDED_REPEATS:-1}"
}
if [[ $STAGE != refine ]]; then
  half=$((FRAMES / 2))
  t0=$(date +%s)
  render "$WORK/train-a" 0 "$half" 1 &
  render "$WORK/train-b" "$half" "$((FRAMES - half))" 1 &
  wait
  render "$WORK/val" 0 400 7
  t1=$(date +%s)
  echo "full-frame stage: rendered in $((t1 - t0)) s"
  train full resources/pupil/pupil-net.onnx "$EPOCHS" "$WORK/train-a" "$WORK/train-b" "$WORK/val"
  echo "full-frame stage: trained in $(( $(date +%s) - t1 )) s"
fi
if [[ $STAGE != full ]]; then
  # The same frames (seed 1, from index 0) stored at 200 px, in shards of 9000, two at a time.
  t0=$(date +%s)
  shards=()
  for ((start = 0; start < RFRAMES; start += 9000)); do
    n=$((RFRAMES - start < 9000 ? RFRAMES - start : 9000))
    shards+=("$WORK/refine-$start")
    render "$WORK/refine-$start" "$start" "$n" 1 200 &
    if (( ${#shards[@]} % 2 == 0 )); then wait; fi
  done
  wait
  render "$WORK/refine-val" 0 400 7 200
  t1=$(date +%s)
  echo "refining stage: rendered in $((t1 - t0)) s"
  OCCLUDED_REPEATS=3 train refine resources/pupil/pupil-refine.onnx "$REPOCHS" "${shards[@]}" "$WORK/refine-val"
  echo "refining stage: trained in $(( $(date +%s) - t1 )) s"
fi
