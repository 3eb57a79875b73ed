#!/usr/bin/env bash
# Packs what bench/device/gpu_checks.sh needs into .gpu/ (ignored through .git/info/exclude) for a
# lent GPU machine, which has none of our Debian packages: the Release binaries (stripped), every
# shared library they load except glibc's own, the Vulkan loader, glvnd's dispatch libraries (the
# NVIDIA driver's ICD, libGLX_nvidia, needs them, and that image has none) and the Khronos validation layer,
# in one xz tarball (.gpu/echosim-gpu.tar.xz; unpacked it is over the tool's 64 MiB a call). No cached
# volumes: there the GPU makes each case's in seconds.
# Usage, in the repository root after a Release build in build/:
#   bench/device/pack.sh && (device run, carry .gpu) bench/device/gpu_checks.sh
set -euo pipefail
root=$(git rev-parse --show-toplevel)
cd "$root"
grep -qx '/.gpu/' .git/info/exclude 2>/dev/null || echo '/.gpu/' >>.git/info/exclude
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/bin" "$stage/lib" "$stage/lib-std" "$stage/layers"
for b in build/engine/app/echosim build/tests/echosim_tests; do
    [ -x "$b" ] || { echo "pack.sh: $b missing: build Release first (scripts/test does)" >&2; exit 1; }
    strip -o "$stage/bin/$(basename "$b")" "$b"
done
# libstdc++ and libgcc_s go apart: gpu_checks.sh adds them only where the machine lacks them
libs=$( (ldd build/engine/app/echosim; ldd build/tests/echosim_tests;
         ldd /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so
         for l in libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libOpenGL.so.0 libGL.so.1; do
             echo "$l => /usr/lib/x86_64-linux-gnu/$l"; ldd "/usr/lib/x86_64-linux-gnu/$l"; done) |
       awk '/=> \//{print $3}' | sort -u)
for l in $libs; do
    case $(basename "$l") in
        libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*) ;;
        libstdc++*|libgcc_s*) cp -L "$l" "$stage/lib-std/" ;;
        *) cp -L "$l" "$stage/lib/" ;;
    esac
done
cp -L /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so "$stage/layers/"
sed 's#"library_path": *"[^"]*"#"library_path": "./libVkLayer_khronos_validation.so"#' \
    /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json >"$stage/layers/VkLayer_khronos_validation.json"
rm -rf .gpu && mkdir .gpu
tar -C "$stage" -cJf .gpu/echosim-gpu.tar.xz .
du -sh .gpu/echosim-gpu.tar.xz
