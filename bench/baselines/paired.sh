#!/bin/bash
# Issue 10's lavapipe goals, measured against their baseline in the same spell of this shared
# machine: VTK's vtkImageReslice slicing alone (vtk_reslice.py, the geometry of echosim's bench)
# and `echosim bench slice` at 1024 x 1024, alternately, ROUNDS times. The machine's speed drifts
# by tens of per cent over minutes, so an absolute goal met in one spell may be missed in the next;
# the ratio of two runs a minute apart is what says whether echosim is faster than the baseline.
#
# usage: bench/baselines/paired.sh [ROUNDS] [ECHOSIM]   (3 rounds; build/engine/app/echosim)
# prints one line per run and, per round, echosim's rates over the mean of the VTK runs either side.
set -euo pipefail
rounds=${1:-3}
echosim=${2:-build/engine/app/echosim}
here=$(dirname "$0")
[ -x "$echosim" ] || { echo "paired.sh: $echosim is not built (scripts/run builds it)" >&2; exit 1; }

vtk() { /usr/bin/python3 "$here/vtk_reslice.py" --seconds 5 | sed -n 's/.*fps=\([0-9.]*\).*/\1/p'; }
ours() {
    "$echosim" bench slice --filter 'lavapipe/1024x1024' --repetitions 3 |
        awk '/^  (slice|slice-only)\/lavapipe\/1024x1024/ { for (i = 1; i <= NF; ++i) if ($i ~ /^fps=/) print $1, substr($i, 5) }'
}

before=$(vtk)
echo "vtk $before"
for round in $(seq 1 "$rounds"); do
    rates=$(ours)
    after=$(vtk)
    echo "$rates" | sed 's/^/echosim /'
    echo "vtk $after"
    echo "$rates" | awk -v r="$round" -v a="$before" -v b="$after" \
        '{ printf "round %d: %s %.0f fps = %.2f x VTK (%.0f, %.0f fps either side)\n", r, $1, $2, $2 / ((a + b) / 2), a, b }'
    before=$after
done
