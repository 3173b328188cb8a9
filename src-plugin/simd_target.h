/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   The pair kernel's build targets. On x86-64 with GCC or Clang, the kernel's hot functions are
   compiled twice, for the baseline (SSE2) and, through __attribute__((target("avx2"))), for
   AVX2, and the pair picks one at run time (keyword kernel). Why attributes and not one source
   compiled twice with -mavx2: such a source instantiates ordinary inline functions too
   (std::vector's, the laws' helpers that are not forced inline) under the same names in both
   objects, and the linker keeps one copy, which may be the AVX2 one, run on a CPU without AVX2.
   The attribute confines AVX2 to the functions that carry it.
------------------------------------------------------------------------- */

#ifndef TBAGS_SIMD_TARGET_H
#define TBAGS_SIMD_TARGET_H

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__AVX2__) && !defined(TBAGS_NO_AVX2_CLONE)
#define TBAGS_HAVE_AVX2_CLONE 1
#define TBAGS_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define TBAGS_TARGET_AVX2
#endif

// the scatter pass without GCC's SLP vectorizer, whose shuffles cost more than they saved (it
// came with the packed atom records; the two took the benchmark from 358 to 314 instructions per
// contact-step); the optimize attribute is GCC's own, other compilers get noinline only
#if defined(__GNUC__) && !defined(__clang__)
#define TBAGS_NOINLINE_NO_SLP __attribute__((noinline, optimize("no-tree-slp-vectorize")))
#else
#define TBAGS_NOINLINE_NO_SLP __attribute__((noinline))
#endif

#endif
