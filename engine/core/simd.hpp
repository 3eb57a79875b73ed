// Vectorised kernels without giving up the portable binary: a function marked ECHOSIM_SIMD_CLONES
// is compiled for AVX-512, for AVX2 + FMA and for the x86-64 baseline, and the loader picks the
// best the processor has (GCC's target_clones). Elsewhere the mark does nothing. The clones may round
// differently (fused multiply-adds, the lanes of a vectorised sum), so such a kernel's last bits can
// differ from one processor to another; on one machine they repeat exactly.
// Not under ThreadSanitizer: the loader runs the clones' resolvers before TSan's runtime is up, and
// an instrumented resolver crashes the program before main.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_THREAD__)
#define ECHOSIM_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define ECHOSIM_SIMD_CLONES
#endif

// The helpers (templates, lambdas) a cloned kernel calls are compiled for the baseline unless they
// are inlined into each clone: ECHOSIM_INLINE makes sure they are.
#if defined(__GNUC__)
#define ECHOSIM_INLINE __attribute__((always_inline))
#else
#define ECHOSIM_INLINE
#endif
