#!/usr/bin/env bash
# Every command that writes, when the disk fills up and when its folder is read-only: it stops with
# a message naming the file or folder, exits non-zero, leaves no temporary file behind, and the
# files already there stay exactly as they were.
#   write_faults.sh ECHOSIM WORK
# A full disk is a file-size limit (prlimit --fsize): writes past it fail with EFBIG, as they would
# with ENOSPC, at the same place. A read-only folder is one the user cannot write; as root (CI) the
# commands run as nobody, from a copy of the binary nobody can reach.
set -euo pipefail
echosim=$1
work=$2
rm -rf "$work"
mkdir -p "$work/in"
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# inputs, made without limits. The commands are the cheapest of each kind (bench: one fit row, the
# steepest descent's 7 s, two minutes under AddressSanitizer, writing the same JSON)
"$echosim" measure --out "$work/in/m.csv" >/dev/null
"$echosim" phantom --out "$work/in/s.mha" --frames 8 --pixel-mm 0.5 >/dev/null 2>&1
"$echosim" reconstruct --sweep "$work/in/s.mha" --out "$work/in/v.nrrd" --voxel-mm 1 >/dev/null 2>&1

# OUT is replaced by the output folder; the first output named is the one checked
cases=(
  "measure --out OUT/out.csv"
  "fit --data $work/in/m.csv --out OUT/out.json --report OUT/report"
  "render --out OUT/out.png --width 320 --height 200 --gpu cpu"
  "slice --volume $work/in/v.nrrd --out OUT/out.png --cpu"
  "phantom --out OUT/out.mha --frames 8 --pixel-mm 0.5 --labels OUT/map.nrrd"
  "reconstruct --sweep $work/in/s.mha --out OUT/out.nrrd --voxel-mm 1"
  "haptics-demo --out OUT/demo --physics-hz 100"
  "bench fit --filter levenberg --min-time 0.01 --json OUT/out.json"
  "soak --seconds 10 --deadlines report --json OUT/out.json"
)

# the files a case's output folder holds before it runs: old results that must survive
seed() {
  local dir=$1
  mkdir -p "$dir/demo" "$dir/report"
  for f in out.csv out.json out.png out.mha out.labels.mha map.nrrd out.nrrd demo/summary.json demo/force_log.csv \
           report/report.json; do
    echo "old result $f" >"$dir/$f"
  done
}
check_untouched() {
  local dir=$1 what=$2
  while IFS= read -r f; do
    local rel=${f#"$dir/"}
    [[ "$(cat "$f")" == "old result $rel" ]] || fail "$what: $rel was changed"
  done < <(find "$dir" -type f)
  local stray
  stray=$(find "$dir" -name '*.partial' -o -name '*.partial-*' -o -name '*.echosim-partial-*' -o -name '.echosim-writing-*' | head -1)
  [[ -z "$stray" ]] || fail "$what: left $stray behind"
}

# 1. the disk fills up: 512 bytes per file is less than any command writes
i=0
for c in "${cases[@]}"; do
  i=$((i + 1))
  dir="$work/full$i"
  seed "$dir"
  args=${c//OUT/$dir}
  set +e
  err=$(prlimit --fsize=512 -- "$echosim" $args 2>&1 >/dev/null)
  rc=$?
  set -e
  name=${c%% *}
  [[ $rc -ne 0 ]] || fail "$name with a full disk: exit 0"
  [[ $rc -ne 153 && $rc -ne 134 && $rc -lt 128 ]] || fail "$name with a full disk: killed by a signal (exit $rc): $err"
  [[ "$err" == *"$dir"* ]] || fail "$name with a full disk: the message does not name the file: $err"
  [[ "$err" == *"File too large"* || "$err" == *"write"* ]] || fail "$name with a full disk: the message does not say the write failed: $err"
  check_untouched "$dir" "$name with a full disk"
  echo "full disk: $name: exit $rc: $(echo "$err" | tail -1)"
done

# 2. a read-only folder
runner=()
bin=$echosim
if [[ $(id -u) -eq 0 ]]; then
  runner=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  copy=$(mktemp -d /tmp/echosim-write-faults-XXXXXX)
  trap 'rm -rf "$copy"' EXIT
  cp "$echosim" "$copy/echosim"
  chmod 755 "$copy" "$copy/echosim"
  bin=$copy/echosim
  chmod o+rx "$work" "$work/in"
  chmod o+r "$work"/in/*
fi
i=0
for c in "${cases[@]}"; do
  i=$((i + 1))
  dir="$work/ro$i"
  seed "$dir"
  chmod -R a-w "$dir"
  chmod -R o+rX "$dir"
  args=${c//OUT/$dir}
  set +e
  err=$(cd "$work" && "${runner[@]}" "$bin" $args 2>&1 >/dev/null)
  rc=$?
  set -e
  chmod -R u+w "$dir"
  name=${c%% *}
  [[ $rc -ne 0 ]] || fail "$name in a read-only folder: exit 0"
  [[ $rc -lt 128 ]] || fail "$name in a read-only folder: killed by a signal (exit $rc): $err"
  [[ "$err" == *"$dir"* ]] || fail "$name in a read-only folder: the message does not name the folder: $err"
  check_untouched "$dir" "$name in a read-only folder"
  echo "read-only folder: $name: exit $rc: $(echo "$err" | tail -1)"
done

[[ $failures -eq 0 ]] || { echo "$failures failure(s)" >&2; exit 1; }
echo "every command that writes survived a full disk and a read-only folder"
