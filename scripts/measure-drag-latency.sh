#!/usr/bin/env bash
# End-to-end drag latency of the studio under Xvfb (docs/benchmarks.md, "Responsive drag"):
# starts fovea-studio with FOVEA_LATENCY_LOG=1 on a private Xvfb display, drags the gaze yaw
# slider with xdotool (real X input: press, N moves over ~0.6 s, release), waits for the
# refined trace, quits, and summarises what the studio logged: per move the GUI thread's time,
# per drawn result the latency from the move that asked for it to the swapped frame.
# Usage: scripts/measure-drag-latency.sh [STUDIO] [extra studio args, e.g. --follow-gaze]
# FOVEA_DRAG_RESOLUTION=N (25..100) sets the preference "3-D view resolution while dragging"
# for the run (default: the studio's default, 50 %).
set -euo pipefail
studio=${1:-build/default/app/fovea-studio}
shift || true
log=$(mktemp)
home=$(mktemp -d)  # fresh settings: no autosave-recovery question from an earlier run
display=:$((90 + RANDOM % 100))
Xvfb "$display" -screen 0 1920x1080x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null || true; rm -rf "$log" "$home"' EXIT
sleep 1
if [ -n "${FOVEA_DRAG_RESOLUTION:-}" ]; then
  mkdir -p "$home/config/FoveatedARStudio"
  printf '[preferences]\ndragResolutionPercent=%s\n' "$FOVEA_DRAG_RESOLUTION" >"$home/config/FoveatedARStudio/fovea-studio.conf"
fi
HOME=$home XDG_CONFIG_HOME=$home/config XDG_DATA_HOME=$home/data XDG_CACHE_HOME=$home/cache \
  DISPLAY=$display FOVEA_LATENCY_LOG=1 "$studio" "$@" 2>"$log" &
app=$!
for _ in $(seq 120); do grep -q '^yaw-slider:' "$log" && break; sleep 0.5; done
read -r _ x y xend < <(grep '^yaw-slider:' "$log")
sleep 2  # the first refined trace
export DISPLAY=$display
xdotool mousemove "$x" "$y"
sleep 0.5
xdotool mousedown 1
sleep 0.1
steps=36
for i in $(seq 1 $steps); do
  xdotool mousemove $((x + (xend - x) * i / steps)) "$y"
  sleep 0.016
done
xdotool mouseup 1
sleep 3
kill "$app" 2>/dev/null || true
wait "$app" 2>/dev/null || true
summary() {  # name, then numbers on stdin: count, median, 90th percentile, max
  sort -n | awk -v n="$1" '{a[NR]=$1} END {if (NR==0) {print n ": none"; exit}
    printf "%s: %d samples, median %d ms, p90 %d ms, max %d ms\n", n, NR, a[int((NR+1)/2)], a[int(NR*0.9+0.5)], a[NR]}'
}
grep '^gui:' "$log" | awk '{print $2}' | summary "GUI thread per move"
grep "^latency: coarse" "$log" | awk "{print \$3}" | summary "move -> drawn coarse rays"
grep "^latency: coarse" "$log" | awk "{print \$5}" | cut -d. -f1 | summary "coarse trace compute"
grep "^latency: coarse" "$log" | awk "{print \$7}" | cut -d. -f1 | summary "3-D view paint of that frame"
grep "^latency: coarse" "$log" | awk "{print \$9}" | summary "move -> result on the GUI thread"
echo "coarse frames drawn: $(grep -c '^latency: coarse' "$log" || true) for $steps moves"
