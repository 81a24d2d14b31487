#!/usr/bin/env bash
# Trains the learned pupil detector's two stages (scripts/train_pupil_net.py) and writes
# resources/pupil/pupil-net.onnx (the whole frame at 96 px) and pupil-refine.onnx (a 96 px
# window of the frame at 200 px around the first stage's centre), each with a .json of its
# validation figures. Not part of the test command: the shipped models are what the tests
# check. Deterministic by seed (renderer seeds 1 for training, 7 for validation; PyTorch seed
# 31). The shipped models: the full-frame stage 18000 frames of subset train, 6000 of train_hard
# (the hard subset's combination in the training's bands) and 6000 of train_partial (train's
# draws, every frame cut at the pupil), three more 3 x 3 convolutions at the 6 x 6 level
# (--context 3, a receptive field over the whole input), closed eyes' visibility loss weighted
# 10x, 18 epochs on one thread in 30 minutes; the refining stage 72000 train, 18000 train_hard
# and 18000 train_partial frames, those with a pupil less than 60 % visible shown three times an
# epoch, --context 3, 9 epochs in 81 minutes, then 5 more from those weights at a third of the
# peak learning rate (--refine-finetune-epochs) in 50 minutes, each beside another training,
# then 4 more from those at the same rate with windows that scale with the pupil (--refine-scale-
# epochs; T drawn from 90-150 px, --refine-scale-above; learned_pupil_detector.h) in 41 minutes;
# rendering 18 minutes on two cores while a build ran beside it. The two stages train side by
# side, one core each. One thread each: two intra-op threads on a shared two-core machine stall
# at their barriers (up to 17 min an epoch while builds ran). The trainer stops at --max-minutes
# whatever the epoch; the .json files give the epochs it ran.
#   scripts/train-pupil-net.sh [--stage full|refine|both] [--frames N] [--hard-frames N] [--partial-frames N]
#       [--epochs E] [--refine-frames N] [--refine-hard-frames N] [--refine-partial-frames N]
#       [--refine-epochs E] [--refine-finetune-epochs E] [--refine-scale-epochs E] [--refine-scale-above LO:HI]
#       [--max-minutes M] [--refine-max-minutes M] [--work DIR]
# FOVEA_CLI overrides the fovea-cli to use (default: build/default/app/fovea-cli, built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES=18000 HARD=6000 PARTIAL=6000 EPOCHS=18 MINUTES=80 WORK=/tmp/fovea-pupil-train STAGE=both RFRAMES=72000 RHARD=18000
REPOCHS=9 CLOSED_WEIGHT=10 RPARTIAL=18000 RMINUTES=120 RCONTEXT=3 FCONTEXT=3 RFINE=5 RFINE_LR=1e-3
RSCALE=4 RSCALE_ABOVE=90:150
while [[ $# -gt 0 ]]; do
  case "$1" in
    --stage) STAGE=$2; shift 2 ;;
    --refine-frames) RFRAMES=$2; shift 2 ;;
    --refine-epochs) REPOCHS=$2; shift 2 ;;
    --refine-finetune-epochs) RFINE=$2; shift 2 ;;
    --refine-scale-epochs) RSCALE=$2; shift 2 ;;
    --refine-scale-above) RSCALE_ABOVE=$2; shift 2 ;;
    --refine-max-minutes) RMINUTES=$2; shift 2 ;;
    --refine-hard-frames) RHARD=$2; shift 2 ;;
    --refine-partial-frames) RPARTIAL=$2; shift 2 ;;
    --hard-frames) HARD=$2; shift 2 ;;
    --partial-frames) PARTIAL=$2; shift 2 ;;
    --frames) FRAMES=$2; shift 2 ;;
    --epochs) EPOCHS=$2; shift 2 ;;
    --work) WORK=$2; shift 2 ;;
    --max-minutes) MINUTES=$2; shift 2 ;;
    *) echo "train-pupil-net.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
case "$STAGE" in full|refine|both) ;; *) echo "train-pupil-net.sh: --stage $STAGE: full, refine or both" >&2; exit 2 ;; esac
# PyTorch from Debian (the system interpreter: a pyenv or venv python3 does not see it).
# python3-opencv: the scaled refining windows' INTER_AREA, the same OpenCV 4.6 as the C++ side's.
if ! /usr/bin/python3 -c "import torch, onnx, cv2" 2>/dev/null; then
  sudo=""; [[ $(id -u) -ne 0 ]] && sudo=sudo
  pkgs=(python3-torch python3-onnx python3-opencv)
  $sudo apt-get install -y "${pkgs[@]}" || { $sudo apt-get update && $sudo apt-get install -y "${pkgs[@]}"; }
fi
CLI=${FOVEA_CLI:-build/default/app/fovea-cli}
if [[ ! -x $CLI ]]; then cmake --preset default && cmake --build --preset default --target fovea-cli; fi
mkdir -p "$WORK"
render() {  # DIR START COUNT SEED [SIZE [SUBSET]]
  local size=${5:-96} subset=${6:-train}
  if [[ -f $1/dataset.json ]] && grep -q "\"frames\": $3," "$1/dataset.json" && grep -q "\"start\": $2," "$1/dataset.json" && grep -q "\"seed\": $4," "$1/dataset.json" && grep -q "\"subset\": \"$subset\"" "$1/dataset.json" && tr -d ' \n' < "$1/dataset.json" | grep -q "\"stored_size_px\":\[$size,"; then return; fi
  nice -n 10 "$CLI" eye-dataset --out "$1" --start "$2" --frames "$3" --seed "$4" --size "$size" --subset "$subset" --no-png
}
train() {  # STAGE OUT EPOCHS DIR... (the last DIR is the validation set)
  local stage=$1 out=$2 epochs=$3; shift 3
  local args=() n=$#
  for ((k = 1; k < n; k++)); do args+=(--data "${!k}"); done
  nice -n 10 /usr/bin/python3 scripts/train_pupil_net.py --stage "$stage" "${args[@]}" --val "${!n}" --out "$out" \
    --epochs "$epochs" --max-minutes "${LIMIT:-$MINUTES}" --threads 1 --occluded-repeats "${OCCLUDED_REPEATS:-1}" \
    --closed-weight "${CLOSED:-3}" --context "${CONTEXT:-0}" ${EXTRA:-}
}
# Rendering: the full-frame stage's frames at 96 px, the refining stage's at 200 px in shards of
# 9000 (the same seed-1 frames from index 0, and train_hard frames from index 0), two at a time.
t0=$(date +%s)
pids=()
wait_all() {  # every background job, failing if one failed
  local p
  for p in "${pids[@]}"; do wait "$p"; done
  pids=()
}
queue() {  # render in the background, two at a time
  render "$@" &
  pids+=($!)
  if (( ${#pids[@]} == 2 )); then wait_all; fi
}
full_dirs=() shards=()
shard() {  # PREFIX TOTAL SUBSET: seed-1 frames from index 0 at 200 px, in shards of 9000
  local start
  for ((start = 0; start < $2; start += 9000)); do
    shards+=("$1-$start")
    queue "$1-$start" "$start" "$(($2 - start < 9000 ? $2 - start : 9000))" 1 200 "$3"
  done
}
if [[ $STAGE != refine ]]; then
  half=$((FRAMES / 2))
  full_dirs=("$WORK/train-a" "$WORK/train-b" "$WORK/train-hard")
  if ((PARTIAL > 0)); then full_dirs+=("$WORK/train-partial"); fi
  queue "$WORK/train-a" 0 "$half" 1
  queue "$WORK/train-b" "$half" "$((FRAMES - half))" 1
  queue "$WORK/train-hard" 0 "$HARD" 1 96 train_hard
  if ((PARTIAL > 0)); then queue "$WORK/train-partial" 0 "$PARTIAL" 1 96 train_partial; fi
  queue "$WORK/val" 0 400 7
fi
if [[ $STAGE != full ]]; then
  shard "$WORK/refine" "$RFRAMES" train
  shard "$WORK/refine-hard" "$RHARD" train_hard
  shard "$WORK/refine-partial" "$RPARTIAL" train_partial
  queue "$WORK/refine-val" 0 400 7 200
fi
wait_all
t1=$(date +%s)
echo "rendered in $((t1 - t0)) s"
# Training: the two stages side by side, one thread each (the refining stage's windows come from
# the true centres, jittered, not from the first stage: the two are independent).
if [[ $STAGE != refine ]]; then
  CLOSED=$CLOSED_WEIGHT CONTEXT=$FCONTEXT train full resources/pupil/pupil-net.onnx "$EPOCHS" "${full_dirs[@]}" "$WORK/val" &
  pids+=($!)
fi
if [[ $STAGE != full ]]; then
  refine() {  # REPOCHS epochs from random weights, RFINE more from them at a lower peak rate, then
    # RSCALE more from those at that rate with scaled windows (each phase skipped when 0 epochs)
    local rargs=("${shards[@]}" "$WORK/refine-val") out=resources/pupil/pupil-refine.onnx
    local phases=("first $REPOCHS" "finetune $RFINE" "scale $RSCALE") prev="" name epochs k extra last=0
    for k in 0 1 2; do read -r name epochs <<< "${phases[k]}"; ((epochs > 0)) && last=$k; done
    for k in 0 1 2; do
      read -r name epochs <<< "${phases[k]}"
      ((epochs > 0)) || continue
      extra="--checkpoint $WORK/refine-$name.pt"
      [[ -n $prev ]] && extra+=" --init $prev --max-lr $RFINE_LR"
      ((k == 2)) && extra+=" --scale-above $RSCALE_ABOVE"
      OCCLUDED_REPEATS=3 CONTEXT=$RCONTEXT LIMIT=$RMINUTES EXTRA="$extra" \
        train refine "$( ((k == last)) && echo "$out" || echo "$WORK/refine-$name.onnx")" "$epochs" "${rargs[@]}"
      prev=$WORK/refine-$name.pt
    done
  }
  refine &
  pids+=($!)
fi
wait_all
echo "trained in $(( $(date +%s) - t1 )) s"
