#!/usr/bin/env bash
# Smoke test of the window: under Xvfb, `echosim run` presents frames while it is resized,
# minimised and made fullscreen, then exits cleanly with the validation layer silent.
set -euo pipefail
echosim=$1
source "$(dirname "$0")/own_xvfb.sh"
log=$(mktemp)
work=$(mktemp -d)
trap 'rm -rf "$log" "$work"' EXIT
# a small volume of the user's own (a short, coarse sweep reconstructed), shown live beside the scene
"$echosim" phantom --frames 24 --pixel-mm 0.3 --out "$work/s.mha" >/dev/null
"$echosim" reconstruct --sweep "$work/s.mha" --out "$work/v.nrrd" --voxel-mm 0.5 >/dev/null 2>&1
own_xvfb_cleanup() { rm -rf "$log" "$work"; }
own_xvfb 1920x1080x24
set +e
"$echosim" run --frames 80 --exercise --width 800 --height 600 \
  --volume "$work/v.nrrd" --labels "$work/v.labels.nrrd" --gpu cpu --validation >"$log" 2>&1
rc=$?
set -e
cat "$log"
[[ $rc -eq 0 ]] || { echo "FAIL: echosim run exited $rc"; exit 1; }
grep -q "presented 80 frames" "$log" || { echo "FAIL: did not present 80 frames"; exit 1; }
# the frames came through the one runner's step (runner/runner.hpp): at least one step a frame
ran=$(sed -n 's/.*the runner stepped \([0-9]*\) times.*/\1/p' "$log")
[[ ${ran:-0} -ge 80 ]] || { echo "FAIL: the runner stepped ${ran:-0} times for 80 frames"; exit 1; }
grep -q "echographic volume: $work/v.nrrd with labels" "$log" || { echo "FAIL: the user's volume was not taken"; exit 1; }
# resize (frame 10), fullscreen (30), windowed (40), resize (50): the swapchain is remade each time
created=$(sed -n 's/.*swapchain created \([0-9]*\) times.*/\1/p' "$log")
[[ ${created:-0} -ge 3 ]] || { echo "FAIL: swapchain created ${created:-0} times, expected at least 3"; exit 1; }
! grep -q "vulkan validation" "$log" || { echo "FAIL: validation messages"; exit 1; }
# the physics thread ran beside the window and the scripted press (12 mm) met the tissue
steps=$(sed -n 's/.*physics stepped \([0-9]*\) times.*/\1/p' "$log")
[[ ${steps:-0} -ge 100 ]] || { echo "FAIL: physics stepped ${steps:-0} times"; exit 1; }
force=$(sed -n 's/.*last probe force \([0-9.]*\) N.*/\1/p' "$log")
awk -v f="${force:-0}" 'BEGIN { exit !(f > 1.0 && f < 100.0) }' || { echo "FAIL: probe force ${force:-none} N"; exit 1; }
echo "PASS"
