#!/usr/bin/env bash
# The checks a lent GPU machine is used for (device tool; see bench/device/pack.sh), in one call:
#  1. the scene rendered headless on that GPU (does the device open at all);
#  2. the compute kernels against their CPU twins on that GPU, validation layer on
#     (ECHOSIM_TEST_GPU=discrete; the reference-image tests, and the two that expect lavapipe by
#     name, hold for lavapipe alone and are left out);
#  3. `echosim bench slice` (the real-GPU rows; no lavapipe there) into $OUT/slice_gpu.json;
#  4. a pressed slice to PNG on the GPU and on the CPU twin, to look at side by side.
set -uo pipefail
cd "$(git rev-parse --show-toplevel 2>/dev/null || pwd)"
out=${OUT:-/tmp/gpu_checks}; mkdir -p "$out"
g=$(mktemp -d)  # the unpacked binaries, libraries, layer and cached volume
tar -C "$g" -xJf .gpu/echosim-gpu.tar.xz || exit 1
export LD_LIBRARY_PATH=$g/lib VK_LAYER_PATH=$g/layers XDG_CACHE_HOME=$g/cache ECHOSIM_ASSETS=$PWD/assets
if ldd $g/bin/echosim | grep -q 'not found'; then export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$g/lib-std; fi
ldd $g/bin/echosim | grep 'not found'
for icd in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
           /etc/vulkan/icd.d/nvidia_icd.json; do
    [ -f "$icd" ] && { export VK_DRIVER_FILES=$icd; break; }
done
echo "ICD: ${VK_DRIVER_FILES:-none found}"
if [ -n "${VK_DRIVER_FILES:-}" ]; then  # what the driver's library lacks, if anything
    icd_lib=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' "$VK_DRIVER_FILES")
    for f in $(ldconfig -p | awk -v l="$icd_lib" '$1 == l {print $NF}') $(find /usr/local/nvidia -name "$icd_lib" 2>/dev/null); do
        echo "$f:"; LD_LIBRARY_PATH=$g/lib ldd "$f" 2>&1 | grep 'not found'
    done
fi
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv 2>&1
gpu=${ECHOSIM_CHECK_GPU:-discrete}  # another for a dry run here: cpu
bench_args=${ECHOSIM_CHECK_BENCH_ARGS:-}  # e.g. --filter 'slice-only' for a dry run
step() { echo "== $*"; }
step "render headless on the GPU"
VK_LOADER_DEBUG=error,warn timeout 120 $g/bin/echosim render --gpu $gpu --out "$out/render_gpu.png" 2>&1 | tail -3
step "kernels vs CPU twins"
tests='EchoImageGpu.*:Compute.*:Context.*:FramePasses.*:LogCompress*:ImagePanel.*'
lavapipe_only='*Reference*:Context.StartsOnLavapipe*:Context.UnknownGpuName*'
ECHOSIM_TEST_GPU=$gpu timeout 240 $g/bin/echosim_tests --gtest_filter="$tests:-$lavapipe_only" 2>&1 |
    tee "$out/tests_gpu.log" | grep -E '^\[  (FAILED|PASSED) |validation|^\[=='
step "bench slice"
timeout 240 $g/bin/echosim bench slice --gpu $gpu --repetitions 3 $bench_args --json "$out/slice_gpu.json" 2>&1 |
    tee "$out/bench.log" | grep -E '^\| |no .* rows'
step "slice images"
for how in "--gpu $gpu" --cpu; do
    name=$( [ "$how" = --cpu ] && echo twin || echo gpu )
    timeout 120 $g/bin/echosim slice $how --force 12 --out "$out/slice_$name.png" 2>&1 | tail -3
done
ls -la "$out"
