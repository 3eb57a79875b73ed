#!/usr/bin/env bash
# The force-feedback arms from the command line. `echosim devices` says whether OpenHaptics is
# installed (if not, where it looked and what to install; with the tests' fake libHD, the arm's
# figures); `run --device openhaptics` refuses a missing library with the same sentence (exit 2);
# under Xvfb, `run --device simulated-arm` moves the probe through the haptic loop from the simulated
# arm's own servo, and `run --device openhaptics` opens the fake arm, then stops it in order: zero
# force, the servo, the arm.
set -euo pipefail
echosim=$1
fake=$2
source "$(dirname "$0")/own_xvfb.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

ECHOSIM_OPENHAPTICS_LIBRARY="$work/none/libHD.so" "$echosim" devices >"$work/devices.txt"
cat "$work/devices.txt"
grep -q "simulated arm (simulated): always available" "$work/devices.txt" || fail "the simulated arm is not listed"
grep -q "3D Systems Touch / Phantom (OpenHaptics HD): OpenHaptics' libHD.so not found (.*$work/none/libHD.so" "$work/devices.txt" ||
  fail "a missing OpenHaptics is not said with where it was looked for"
grep -q "install 3D Systems' OpenHaptics for Linux" "$work/devices.txt" || fail "no word of what to install"
ECHOSIM_OPENHAPTICS_LIBRARY="$fake" "$echosim" devices --json >"$work/devices.json"
grep -q '"name": "3D Systems Touch"' "$work/devices.json" || fail "the fake arm is not listed by its model"
grep -q '"library_found": true' "$work/devices.json" || fail "the fake libHD is not said found"

# a small volume of our own, so no case volume is made (a minute and a half)
"$echosim" phantom --frames 24 --pixel-mm 0.3 --out "$work/s.mha" >/dev/null 2>&1
"$echosim" reconstruct --sweep "$work/s.mha" --out "$work/v.nrrd" --voxel-mm 0.5 >/dev/null 2>&1
# one X server of the test's own for the three runs: xvfb-run's clean-up raced a command that ends at
# once (the missing OpenHaptics, exit 2) and failed with its own exit 5 ("problem while cleaning up
# temporary directory"), twice in this workplace
own_xvfb_cleanup() { rm -rf "$work"; }
own_xvfb 1280x800x24
run() { "$echosim" run --frames 20 --width 640 --height 480 --gpu cpu \
  --volume "$work/v.nrrd" --labels "$work/v.labels.nrrd" "$@"; }

set +e
ECHOSIM_OPENHAPTICS_LIBRARY="$work/none/libHD.so" run --device openhaptics >"$work/missing.log" 2>&1
rc=$?
set -e
cat "$work/missing.log"
[[ $rc -eq 2 ]] || fail "run --device openhaptics without OpenHaptics exited $rc, not 2"
grep -q "OpenHaptics' libHD.so not found" "$work/missing.log" || fail "run did not say OpenHaptics is missing"

run --device simulated-arm >"$work/arm.log" 2>&1 || { cat "$work/arm.log"; fail "run --device simulated-arm exited $?"; }
cat "$work/arm.log"
grep -q "simulated arm: connected: its own servo thread at 1000 Hz" "$work/arm.log" || fail "the simulated arm did not connect"
ticks=$(sed -n 's/.*haptic loop ticked \([0-9]*\) times.*/\1/p' "$work/arm.log")
[[ ${ticks:-0} -ge 100 ]] || fail "the haptic loop ticked ${ticks:-0} times"

ECHOSIM_OPENHAPTICS_LIBRARY="$fake" run --device openhaptics >"$work/fake.log" 2>&1 || { cat "$work/fake.log"; fail "run with the fake arm exited $?"; }
cat "$work/fake.log"
grep -q "3D Systems Touch: connected: HD device 1, serial FAKE-0001" "$work/fake.log" || fail "the fake arm did not connect"
echo "arm devices: OK"
