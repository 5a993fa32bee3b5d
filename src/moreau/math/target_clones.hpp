#pragma once
// Function multi-versioning for the hottest fluid loops: g++ compiles an x86-64-v4 (AVX-512), an
// x86-64-v3 (AVX2) and a baseline version of the function and picks one when the program loads,
// by the CPU it runs on. Clang 14 resolves "arch=" clones wrongly — it ran the AVX-512 clone on an
// AMD EPYC without AVX-512 (SIGILL) — so clang builds (the sanitizer build) keep the baseline only.
#if defined(__clang__)
#define MOREAU_TARGET_CLONES
#else
#define MOREAU_TARGET_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
