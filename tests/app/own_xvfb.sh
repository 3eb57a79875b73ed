# Sourced by the tests that need an X server: `own_xvfb WxHxD` starts Xvfb on a display it picks
# itself (-displayfd: the server takes a free display's lock and writes its number once it accepts
# connections), exports DISPLAY, and stops the server when the test exits. A display number picked
# by the test (or by xvfb-run -a, which looks for a free lock file and then starts) can be taken, or
# left locked by a killed run, and a fixed wait for readiness ran out under load in this workplace.
# -noreset: an X server resets when its last client leaves, and a client connecting then is refused;
# the kiosk test's xdotool polls came and went while echosim, slow to start beside two CPU hogs,
# connected ("Failed to open display", one run in three). OWN_XVFB_LOG=F keeps the servers' stderr.
own_xvfb() {
  command -v Xvfb >/dev/null || { echo "Xvfb missing: scripts/deps installs xvfb"; exit 1; }
  local ready
  ready=$(mktemp)
  Xvfb -displayfd 3 -screen 0 "$1" -nolisten tcp -noreset 3>"$ready" >/dev/null 2>>"${OWN_XVFB_LOG:-/dev/null}" &
  own_xvfb_pid=$!
  # stopped and waited for: a server still ending removes its socket after the next one (which
  # takes the display its lock left free) made the same, and that one cannot be reached
  trap 'kill $own_xvfb_pid 2>/dev/null && wait $own_xvfb_pid 2>/dev/null; own_xvfb_cleanup' EXIT
  for _ in $(seq 1 600); do
    [[ -s "$ready" ]] && break
    kill -0 $own_xvfb_pid 2>/dev/null || { echo "FAIL: Xvfb ($1) exited before it took a display"; exit 1; }
    sleep 0.1
  done
  [[ -s "$ready" ]] || { echo "FAIL: Xvfb ($1) took no display in 60 s"; exit 1; }
  DISPLAY=:$(head -1 "$ready")
  export DISPLAY
  rm -f "$ready"
}
# a test's own clean-up, run after the server is stopped; a test that has some redefines it
own_xvfb_cleanup() { :; }
