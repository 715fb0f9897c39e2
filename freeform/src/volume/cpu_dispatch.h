#pragma once
// The run-time CPU dispatch of the volume kernels (the FFD binding's, ffd_binding.cpp, and the
// drag pass's, drag_pass.cpp), written once: FREEFORM_CPU_CLONES compiles a function for
// x86-64-v4 (AVX-512), x86-64-v3 (AVX2, FMA) and the baseline, and the loader picks one on the
// machine that runs it; no -march in the build. GCC on x86-64 only (clang's target_clones and
// other targets: the baseline alone); FREEFORM_NO_CPU_DISPATCH switches it off.
// Include it from a kernel's .cpp only: it also silences -Wpsabi for that file, since its lane
// vectors never cross a call boundary (everything is inlined into the clones).

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(FREEFORM_NO_CPU_DISPATCH)
#define FREEFORM_CPU_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define FREEFORM_CPU_CLONES
#endif
/// Inlined into every clone, so that it is compiled for that clone's target.
#define FREEFORM_CPU_INLINE inline __attribute__((always_inline))

#pragma GCC diagnostic ignored "-Wpsabi"
