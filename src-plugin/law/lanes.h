/* T-BAGS DEM toolkit: what the laws' chains over lanes share (contact_chain.h, yarn_chain.h): the
   SIMD pragma of their loops and the access to one lane's column of a 3-row array (a vector's
   x, y, z). Structure of arrays: row k, lane l is a[k][l]. */
#ifndef TBAGS_LAW_LANES_H
#define TBAGS_LAW_LANES_H

#include "vec3.h"

// The loops' pragma. GCC: "ivdep" (the lanes do not depend on each other; the vectoriser's own
// cost model decides). Not "omp simd" there: it gives each local a stage takes by reference (a
// State, a Touch) one copy per lane, an "omp simd array" whose field stores the vectoriser
// cannot do, and the geometry loop stayed scalar (measured on the contact law's State). Other
// compilers: "#pragma omp simd" with -fopenmp-simd (no OpenMP runtime) or OpenMP; else nothing.
#if defined(__GNUC__) && !defined(__clang__)
#define TBAGS_PRAGMA_SIMD _Pragma("GCC ivdep")
#define TBAGS_PRAGMA_SIMD_OR_REDO _Pragma("GCC ivdep")
#elif defined(_OPENMP) || defined(TBAGS_OPENMP_SIMD)
#define TBAGS_PRAGMA_SIMD _Pragma("omp simd")
#define TBAGS_PRAGMA_SIMD_OR_REDO _Pragma("omp simd reduction(| : redo)")
#else
#define TBAGS_PRAGMA_SIMD
#define TBAGS_PRAGMA_SIMD_OR_REDO
#endif

namespace tbags {

// column l of three rows
template <int W> TBAGS_INLINE vec::V3 row3(const double (*r)[W], int l)
{
  return vec::V3{r[0][l], r[1][l], r[2][l]};
}
template <int W> TBAGS_INLINE void set_row3(double (*r)[W], int l, const vec::V3 &v)
{
  r[0][l] = v.x;
  r[1][l] = v.y;
  r[2][l] = v.z;
}

}    // namespace tbags
#endif
