#!/usr/bin/env bash
# The kiosk in a window under Xvfb (issue 32): `echosim run --kiosk` opens fullscreen at the display's
# resolution (a 1920x1080 screen, and a 3840x2160 one), presents its frames with the trainer's start
# screen over them, and exits cleanly with the validation layer silent; then a lesson started on
# another case changes runner in the same window (below). The cases' coarse volumes are made into
# the test's own cache, empty at the start; the records go to its own folder.
set -euo pipefail
echosim=$1
work=$2
source "$(dirname "$0")/own_xvfb.sh"
rm -rf "$work"  # the cache too: the run makes the cases' volumes behind its start screen
mkdir -p "$work"
export XDG_CACHE_HOME="$work/cache" XDG_DATA_HOME="$work/data"
for screen in 1920x1080 3840x2160; do
  log="$work/kiosk-$screen.log"
  # each screen its own server, in a subshell so its exit stops it
  set +e
  (own_xvfb "${screen}x24"; "$echosim" run --kiosk --frames 12 --coarse --gpu cpu --validation) >"$log" 2>&1
  rc=$?
  set -e
  cat "$log"
  [[ $rc -eq 0 ]] || { echo "FAIL: echosim run --kiosk on a $screen screen exited $rc"; exit 1; }
  grep -q "llvmpipe.*, $screen;" "$log" || grep -q ", $screen; " "$log" || { echo "FAIL: the kiosk is not fullscreen at $screen"; exit 1; }
  grep -q "presented 12 frames" "$log" || { echo "FAIL: did not present 12 frames"; exit 1; }
  # no case's volume is cached in the test's cache: the window opened at once, the volume being
  # made behind the start screen (and the making stopped when the run ended)
  grep -q "echographic volume: none yet: case .* is being made" "$log" || { echo "FAIL: the window waited for the case's volume"; exit 1; }
  ! grep -qi "validation reported" "$log" || { echo "FAIL: validation messages"; exit 1; }
done

# A lesson on another case, as a trainee starts one: F5 (the next case: the large patient) and Enter
# on the start screen, tapped into the window by xdotool, while the cases' volumes are still being
# made (none is cached yet: the start screen says how far, and the lesson starts once its case is
# ready). The run changes runner for that case's volumes (and, if the first case's was made before
# F5, once before for it), and the fullscreen window stays: the same X window before and after, the
# desk behind it never shown. The keys are tapped at once (xdotool --delay 0), as fast a tap as a frame can miss:
# GLFW reads the trainer's keys by polling, and a tap between two frames must still count, before
# the probe's keys are read (Q is both a probe key and Ctrl+Alt+Q's).
command -v xdotool >/dev/null || { echo "xdotool missing: scripts/deps installs it"; exit 1; }
log="$work/kiosk-switch.log"
own_xvfb 1280x720x24
"$echosim" run --kiosk --coarse --gpu cpu --validation >"$log" 2>&1 &
app=$!
window=""
for _ in $(seq 1 600); do
  window=$(xdotool search --name "echosim" 2>/dev/null | head -1 || true)
  [[ -n "$window" ]] && grep -q "llvmpipe" "$log" && break
  kill -0 $app 2>/dev/null || break
  sleep 0.5
done
[[ -n "$window" ]] || { cat "$log"; kill $app 2>/dev/null; echo "FAIL: the kiosk's window never showed"; exit 1; }
sleep 2
xdotool key --delay 0 --window "$window" F5 || true
sleep 1
xdotool key --delay 0 --window "$window" Return || true
for _ in $(seq 1 600); do grep -q "a lesson started" "$log" && break; kill -0 $app 2>/dev/null || break; sleep 0.5; done
sleep 3  # the new runner's frames
after=$(xdotool search --name "echosim" 2>/dev/null | tr '\n' ' ' || true)
# the instructor's keys end the kiosk (Esc does not)
xdotool key --delay 0 --window "$window" ctrl+alt+q || true
for _ in $(seq 1 120); do kill -0 $app 2>/dev/null || break; sleep 0.5; done
kill $app 2>/dev/null && echo "the kiosk did not end on Ctrl+Alt+Q: killed"
set +e
wait $app
rc=$?
set -e
cat "$log"
[[ $rc -eq 0 ]] || { echo "FAIL: the kiosk that changed case exited $rc"; exit 1; }
grep -q "a lesson started: extended on case large-patient" "$log" || { echo "FAIL: F5 and Enter did not start a lesson on the large patient"; exit 1; }
[[ "$after" == "$window " ]] || { echo "FAIL: the window was $window before the change of case, '$after' after"; exit 1; }
runners=$(grep -c "the runner stepped" "$log")
[[ $runners -ge 2 && $runners -le 3 ]] || { echo "FAIL: $runners runners, not the first, (the chosen case's,) the lesson's"; exit 1; }
grep -q "echographic volume: none yet" "$log" || { echo "FAIL: the window waited for the case's volume"; exit 1; }
# the kiosk makes every case's images behind the start screen, and its log says how far
grep -Eq "the cases' images: [0-9]+ of [0-9]+ made, the others being made behind the start screen" "$log" ||
  { echo "FAIL: the log does not say how far the cases' images are"; exit 1; }
! grep -qi "validation reported" "$log" || { echo "FAIL: validation messages"; exit 1; }
echo "PASS"
