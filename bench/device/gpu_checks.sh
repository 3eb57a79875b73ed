#!/usr/bin/env bash
# The checks a lent GPU machine is used for (device tool; see bench/device/pack.sh), in one call,
# the most wanted first (a call cut short still brings back what ran). Everything goes to
# $OUT/log.txt; the benchmarks' JSON and three images beside it (the tool brings back 8 files):
#  1. `echosim bench bmode`, the GPU's rows: sweep synthesis, and the live generative and
#     interpolative images pressed, deform included (issue 33: 1024² live >= 1,000 fps);
#  2. `echosim bench ui`: the trainer's frame on its three screens at 1080p and at the 4K kiosk's
#     3840x2160 (issue 32: >= 60 fps on a real GPU), offscreen, each frame waited for;
#  3. `echosim bench e2e`, headless: a probe move to the presented image;
#  4. `echosim bench slice`, the GPU's 512² and 1024² rows (issue 10's 1024² >= 1,000 fps);
#  5. `echosim phantom --case dvt-acute` on the GPU, timed (a case's sweep);
#  6. the compute kernels against their CPU twins on that GPU, validation layer on
#     (ECHOSIM_TEST_GPU; the reference-image tests, and those that expect lavapipe by name, hold for
#     lavapipe alone and are left out);
#  7. a pressed femoral vein, generative on the GPU and on the CPU twin, interpolative on the GPU.
# ECHOSIM_CHECK_ONLY="bmode tests" (of: bmode ui e2e slice phantom tests images) runs those alone.
set -uo pipefail
cd "$(git rev-parse --show-toplevel 2>/dev/null || pwd)"
out=${OUT:-/tmp/gpu_checks}; mkdir -p "$out"
exec > >(tee "$out/log.txt") 2>&1
g=$(mktemp -d)  # the unpacked binaries, libraries and layer; the volumes made here go below it too
tar -C "$g" -xJf .gpu/echosim-gpu.tar.xz || exit 1
export LD_LIBRARY_PATH=$g/lib VK_LAYER_PATH=$g/layers XDG_CACHE_HOME=$g/cache ECHOSIM_ASSETS=$PWD/assets
if ldd $g/bin/echosim | grep -q 'not found'; then export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$g/lib-std; fi
ldd $g/bin/echosim | grep 'not found'
for icd in /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
           /etc/vulkan/icd.d/nvidia_icd.json; do
    [ -f "$icd" ] && { export VK_DRIVER_FILES=$icd VK_ICD_FILENAMES=$icd; break; }
done
echo "ICD: ${VK_DRIVER_FILES:-none found}"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv 2>&1
nproc; date -u
gpu=${ECHOSIM_CHECK_GPU:-discrete}  # another for a dry run here: cpu
rows=${ECHOSIM_CHECK_ROWS:-gpu/}   # the bmode and slice rows of that device (a dry run here: lavapipe/)
e=$g/bin/echosim
only=" ${ECHOSIM_CHECK_ONLY:-bmode ui e2e slice phantom tests images} "
step() { echo; echo "== $* ($(date -u +%T))"; }
wanted() { [[ $only == *" $1 "* ]]; }
if wanted bmode; then step "bench bmode"
timeout 150 $e bench bmode --gpu $gpu --filter "$rows" --repetitions 3 --json "$out/bmode_gpu.json" | grep -E '^\| |^  bmode|rows'
fi
if wanted ui; then step "bench ui (1080p, 4K kiosk)"
timeout 200 $e bench ui --gpu $gpu --json "$out/ui_gpu.json" | grep -E '^\| |^  ui/|rows|rror'
fi
if wanted e2e; then step "bench e2e (headless)"
timeout 90 $e bench e2e --gpu $gpu --filter headless --json "$out/e2e_gpu.json" | grep -E '^\| |^  e2e|rror'
fi
if wanted slice; then step "bench slice"
timeout 90 $e bench slice --gpu $gpu --filter "${rows}(512|1024)" --repetitions 3 --json "$out/slice_gpu.json" | grep -E '^\| |^  slice'
fi
if wanted phantom; then step "phantom, dvt-acute, on the GPU"
/usr/bin/time -f '%e s wall, %U s user' timeout 120 $e phantom --case dvt-acute --gpu $gpu --out "$g/sweep.mha" | tail -3
fi
if wanted tests; then step "kernels vs CPU twins, validation on"
tests=${ECHOSIM_CHECK_TESTS:-'EchoImageGpu.*:Compute.*:FramePasses.*:LogCompress*:ImagePanel.*:BModeGpu.*:GenerativeImage.*:DeformPhysiology.*:ImageCue.*:GuidePass.*:SceneRender.*:ScenePassLeg.*'}
lavapipe_only='*Reference*'
ECHOSIM_TEST_GPU=$gpu timeout 200 $g/bin/echosim_tests --gtest_filter="$tests:-$lavapipe_only" 2>&1 |
    grep -E '^\[  (FAILED|PASSED|     OK) |alidation|against|^\[==|Failure|Expected|Which is|actual' | head -120
fi
if wanted images; then step "a pressed femoral vein at 8 cm, 8 mm"
pose=-43.3256,-49.1126,-84.6396,0.943398,0.094251,-0.010215,0.317825
for how in "gen_gpu --imaging generative --gpu $gpu" "gen_twin --imaging generative --cpu" "interp_gpu --gpu $gpu"; do
    set -- $how; name=$1; shift
    timeout 90 $e slice --case healthy --coarse --pose $pose --press-mm 8 "$@" --out "$out/fv_$name.png" 2>&1 | tail -2
done
fi
date -u; ls -la "$out"
