#!/usr/bin/env bash
# The kiosk in a window under Xvfb (issue 32): `echosim run --kiosk` opens fullscreen at the display's
# resolution (a 1920x1080 screen, and a 3840x2160 one), presents its frames with the trainer's start
# screen over them, and exits cleanly with the validation layer silent. The cases' coarse volumes are
# made into the test's own cache; the records go to its own folder.
set -euo pipefail
echosim=$1
work=$2
command -v xvfb-run >/dev/null || { echo "xvfb-run missing: scripts/deps installs xvfb"; exit 1; }
mkdir -p "$work"
export XDG_CACHE_HOME="$work/cache" XDG_DATA_HOME="$work/data"
for screen in 1920x1080 3840x2160; do
  log="$work/kiosk-$screen.log"
  set +e
  xvfb-run -a -s "-screen 0 ${screen}x24" "$echosim" run --kiosk --frames 12 --coarse --gpu cpu --validation >"$log" 2>&1
  rc=$?
  set -e
  cat "$log"
  [[ $rc -eq 0 ]] || { echo "FAIL: echosim run --kiosk on a $screen screen exited $rc"; exit 1; }
  grep -q "llvmpipe.*, $screen;" "$log" || grep -q ", $screen; " "$log" || { echo "FAIL: the kiosk is not fullscreen at $screen"; exit 1; }
  grep -q "presented 12 frames" "$log" || { echo "FAIL: did not present 12 frames"; exit 1; }
  ! grep -qi "validation reported" "$log" || { echo "FAIL: validation messages"; exit 1; }
done
echo "PASS"
