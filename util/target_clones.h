// RADKIT_TARGET_CLONES: GCC builds an AVX2 clone of a hot loop beside the portable one and
// picks at load time. "avx2" alone enables no FMA, so both clones round identically and
// results do not depend on the CPU.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RADKIT_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RADKIT_TARGET_CLONES
#endif
