#!/bin/bash
# Where a bench row's time goes inside lavapipe's JIT-compiled kernels: llvmpipe compiles each
# compute pipeline to machine code at run time, which perf samples but cannot name (no symbols, no
# perf map). This runs the row, samples it with perf once it is warm, copies the process's anonymous
# executable mappings (the JIT code) out with gdb while it still runs, disassembles them, and prints
# the share of each JIT function (the kernels; a texel-buffer fetch llvmpipe calls shows as its own),
# the share of samples at llvmpipe's per-lane loops over storage-buffer loads and stores, and the
# hottest instructions with the code around them. It found the costs bench/RESULTS.md names for the
# ninth session (the slice's map fetch calls, the display's store loop, the solve's storage loops).
#
# usage: bench/profile/llvmpipe_jit.sh ROW [OUT] [ECHOSIM]
#   ROW: one row of `echosim bench slice`, e.g. 'slice-only/lavapipe/1024x1024/0.3mm'
#   OUT: a directory for perf.data, jit.asm and report.txt (default: a new one under /tmp)
# needs perf (Debian's linux-perf), gdb and objdump; perf_event_paranoid <= 1 or root.
set -euo pipefail
row=${1:?usage: llvmpipe_jit.sh ROW [OUT] [ECHOSIM]}
out=${2:-$(mktemp -d /tmp/llvmpipe_jit.XXXXXX)}
echosim=${3:-build/engine/app/echosim}
for tool in perf gdb objdump python3; do
    command -v "$tool" > /dev/null || { echo "llvmpipe_jit.sh: $tool is not installed" >&2; exit 1; }
done
[ -x "$echosim" ] || { echo "llvmpipe_jit.sh: $echosim is not built" >&2; exit 1; }
mkdir -p "$out"

# the row times frames for 30 s once its inputs are made (4 s at 0.3 mm, 11 s at 0.1 mm, some of it
# in JIT code too: the pressed frame's settling), so 15 s in, its timed loop is running
"$echosim" bench slice --filter "$row" --min-time 30 > "$out/bench.log" 2>&1 &
pid=$!
trap 'kill $pid 2> /dev/null || true' EXIT
sleep "${LLVMPIPE_JIT_DELAY:-15}"
kill -0 "$pid" 2> /dev/null || { echo "llvmpipe_jit.sh: the bench ended early (see $out/bench.log)" >&2; exit 1; }
perf record -q -e cpu-clock -F 4000 -p "$pid" -o "$out/perf.data" -- sleep 4 > /dev/null 2>&1
: > "$out/jit.asm"
grep ' r-xp 00000000 00:00 0' "/proc/$pid/maps" | while read -r range _; do
    start=${range%-*} end=${range#*-}
    gdb -p "$pid" -batch -ex "dump binary memory $out/jit.$start.bin 0x$start 0x$end" > /dev/null 2>&1
    objdump -D -b binary -m i386:x86-64 --adjust-vma="0x$start" "$out/jit.$start.bin" >> "$out/jit.asm"
done
kill "$pid" 2> /dev/null || true
wait "$pid" 2> /dev/null || true
trap - EXIT
perf script -i "$out/perf.data" -F ip 2> /dev/null > "$out/samples.txt"
python3 "$(dirname "$0")/llvmpipe_jit_report.py" "$out/jit.asm" "$out/samples.txt" | tee "$out/report.txt"
echo "(in $out)"
