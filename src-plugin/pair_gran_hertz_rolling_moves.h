/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   pair_style gran/hertz/rolling, kernel part: data movement between the batch's rows
   (law/contact_chain.h) and per-contact or per-atom arrays. Values are only moved, never
   combined, except the force sums of the scatter, which add in the baseline's order.
   The AVX2 versions carry __attribute__((target("avx2"))) and are chosen at run time
   (PairGranHertzRolling::choose_kernel()); included by pair_gran_hertz_rolling_kernel.cpp only.
------------------------------------------------------------------------- */

#ifndef TBAGS_PAIR_GRAN_HERTZ_ROLLING_MOVES_H
#define TBAGS_PAIR_GRAN_HERTZ_ROLLING_MOVES_H

#include "law/contact_chain.h"
#include "simd_target.h"

#include <cstddef>
#ifdef TBAGS_HAVE_AVX2_CLONE
#include <immintrin.h>
#endif

namespace tbags {
namespace moves {

using Batch = contact::Batch;

/* ----------------------------------------------------------------------
   contact history between its per-contact records (NH doubles at b.hist[l]) and the batch
   rows b.h[k][l]: data movement only; with AVX2, 4 contacts at a time (4x4 transposes)
------------------------------------------------------------------------- */

template <int NH> void hist_rows_scalar(Batch &b, int l0, int n)
{
  for (int l = l0; l < n; l++)
    for (int k = 0; k < NH; k++) b.h[k][l] = b.hist[l][k];
}

template <int NH> void rows_hist_scalar(Batch &b, int l0, int n)
{
  for (int l = l0; l < n; l++)
    for (int k = 0; k < NH; k++) b.hist[l][k] = b.h[k][l];
}

#ifdef TBAGS_HAVE_AVX2_CLONE
template <int NH> TBAGS_TARGET_AVX2 void hist_rows_avx2(Batch &b, int n)
{
  int l = 0;
  for (; l + 4 <= n; l += 4) {
    const double *p0 = b.hist[l], *p1 = b.hist[l + 1], *p2 = b.hist[l + 2], *p3 = b.hist[l + 3];
    if (NH == 6) {
      const __m256d a0 = _mm256_loadu_pd(p0), a1 = _mm256_loadu_pd(p1);
      const __m256d a2 = _mm256_loadu_pd(p2), a3 = _mm256_loadu_pd(p3);
      const __m256d t0 = _mm256_unpacklo_pd(a0, a1), t1 = _mm256_unpackhi_pd(a0, a1);
      const __m256d t2 = _mm256_unpacklo_pd(a2, a3), t3 = _mm256_unpackhi_pd(a2, a3);
      _mm256_storeu_pd(&b.h[0][l], _mm256_permute2f128_pd(t0, t2, 0x20));
      _mm256_storeu_pd(&b.h[1][l], _mm256_permute2f128_pd(t1, t3, 0x20));
      _mm256_storeu_pd(&b.h[2][l], _mm256_permute2f128_pd(t0, t2, 0x31));
      _mm256_storeu_pd(&b.h[3][l], _mm256_permute2f128_pd(t1, t3, 0x31));
      const __m128d c0 = _mm_loadu_pd(p0 + 4), c1 = _mm_loadu_pd(p1 + 4);
      const __m128d c2 = _mm_loadu_pd(p2 + 4), c3 = _mm_loadu_pd(p3 + 4);
      _mm256_storeu_pd(&b.h[4][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpacklo_pd(c0, c1)), _mm_unpacklo_pd(c2, c3), 1));
      _mm256_storeu_pd(&b.h[5][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpackhi_pd(c0, c1)), _mm_unpackhi_pd(c2, c3), 1));
    } else {
      const __m128d c0 = _mm_loadu_pd(p0), c1 = _mm_loadu_pd(p1);
      const __m128d c2 = _mm_loadu_pd(p2), c3 = _mm_loadu_pd(p3);
      _mm256_storeu_pd(&b.h[0][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpacklo_pd(c0, c1)), _mm_unpacklo_pd(c2, c3), 1));
      _mm256_storeu_pd(&b.h[1][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(
          _mm_unpackhi_pd(c0, c1)), _mm_unpackhi_pd(c2, c3), 1));
      const __m128d s01 = _mm_loadh_pd(_mm_load_sd(p0 + 2), p1 + 2);
      const __m128d s23 = _mm_loadh_pd(_mm_load_sd(p2 + 2), p3 + 2);
      _mm256_storeu_pd(&b.h[2][l], _mm256_insertf128_pd(_mm256_castpd128_pd256(s01), s23, 1));
    }
  }
  hist_rows_scalar<NH>(b, l, n);
}

template <int NH> TBAGS_TARGET_AVX2 void rows_hist_avx2(Batch &b, int n)
{
  int l = 0;
  for (; l + 4 <= n; l += 4) {
    double *p0 = b.hist[l], *p1 = b.hist[l + 1], *p2 = b.hist[l + 2], *p3 = b.hist[l + 3];
    const __m256d r0 = _mm256_loadu_pd(&b.h[0][l]), r1 = _mm256_loadu_pd(&b.h[1][l]);
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
    if (NH == 6) {
      const __m256d r2 = _mm256_loadu_pd(&b.h[2][l]), r3 = _mm256_loadu_pd(&b.h[3][l]);
      const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
      _mm256_storeu_pd(p0, _mm256_permute2f128_pd(t0, t2, 0x20));
      _mm256_storeu_pd(p1, _mm256_permute2f128_pd(t1, t3, 0x20));
      _mm256_storeu_pd(p2, _mm256_permute2f128_pd(t0, t2, 0x31));
      _mm256_storeu_pd(p3, _mm256_permute2f128_pd(t1, t3, 0x31));
      const __m256d r4 = _mm256_loadu_pd(&b.h[4][l]), r5 = _mm256_loadu_pd(&b.h[5][l]);
      const __m256d w0 = _mm256_unpacklo_pd(r4, r5), w1 = _mm256_unpackhi_pd(r4, r5);
      _mm_storeu_pd(p0 + 4, _mm256_castpd256_pd128(w0));
      _mm_storeu_pd(p1 + 4, _mm256_castpd256_pd128(w1));
      _mm_storeu_pd(p2 + 4, _mm256_extractf128_pd(w0, 1));
      _mm_storeu_pd(p3 + 4, _mm256_extractf128_pd(w1, 1));
    } else {
      _mm_storeu_pd(p0, _mm256_castpd256_pd128(t0));
      _mm_storeu_pd(p1, _mm256_castpd256_pd128(t1));
      _mm_storeu_pd(p2, _mm256_extractf128_pd(t0, 1));
      _mm_storeu_pd(p3, _mm256_extractf128_pd(t1, 1));
      const __m256d r2 = _mm256_loadu_pd(&b.h[2][l]);
      const __m128d lo = _mm256_castpd256_pd128(r2), hi = _mm256_extractf128_pd(r2, 1);
      _mm_store_sd(p0 + 2, lo);
      _mm_storeh_pd(p1 + 2, lo);
      _mm_store_sd(p2 + 2, hi);
      _mm_storeh_pd(p3 + 2, hi);
    }
  }
  rows_hist_scalar<NH>(b, l, n);
}
#endif

#ifdef TBAGS_HAVE_AVX2_CLONE
/* ----------------------------------------------------------------------
   pass 3 for AVX2 (no energy/virial tally): each contact's f, t_i, t_j as one 4-double vector
   (4x4 transposes of the batch rows), added to j's 3 doubles with one 4-wide load, operation
   and store: the 4th lane, the next atom's x component, gets x - (+0) or x + (-0), i.e. its
   own value (j + 1 < nmax: inside the arrays; in order, so nothing is lost). i's sums stay in
   registers over its run of contacts (j is never i). The same additions in the same order as
   batch_scatter(): the same bits.
------------------------------------------------------------------------- */

TBAGS_TARGET_AVX2 TBAGS_INLINE __m256d load3_avx2(const double *p)
{
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p)), _mm_load_sd(p + 2), 1);
}

TBAGS_TARGET_AVX2 TBAGS_INLINE void store3_avx2(double *p, __m256d v)
{
  _mm_storeu_pd(p, _mm256_castpd256_pd128(v));
  _mm_store_sd(p + 2, _mm256_extractf128_pd(v, 1));
}

// rows r0, r1, r2 (4 contacts each) and a constant 4th row z: c[k] = (r0[k], r1[k], r2[k], z)
TBAGS_TARGET_AVX2 TBAGS_INLINE void rows3_cols(const double *r0, const double *r1,
                                               const double *r2, __m256d z, __m256d c[4])
{
  const __m256d a0 = _mm256_loadu_pd(r0), a1 = _mm256_loadu_pd(r1), a2 = _mm256_loadu_pd(r2);
  const __m256d t0 = _mm256_unpacklo_pd(a0, a1), t1 = _mm256_unpackhi_pd(a0, a1);
  const __m256d t2 = _mm256_unpacklo_pd(a2, z), t3 = _mm256_unpackhi_pd(a2, z);
  c[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
  c[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  c[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
  c[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}

template <int NEWTON>
TBAGS_TARGET_AVX2 __attribute__((noinline)) void scatter_avx2(const Batch &b, int n, double *f,
                                                              double *torque, int nlocal, int nmax)
{
  const __m256d pz = _mm256_setzero_pd(), mz = _mm256_set1_pd(-0.0);
  const int jlast = nmax - 1;    // j < jlast: the 4th lane is inside the arrays
  int i = b.i[0];
  double *fip = f + 3 * (std::ptrdiff_t) i, *tip = torque + 3 * (std::ptrdiff_t) i;
  __m256d fi = load3_avx2(fip), ti = load3_avx2(tip);
  for (int l0 = 0; l0 < n; l0 += 4) {    // rows hold N (multiple of 4) entries
    __m256d cf[4], cti[4], ctj[4];
    rows3_cols(&b.f[0][l0], &b.f[1][l0], &b.f[2][l0], pz, cf);
    rows3_cols(&b.ti[0][l0], &b.ti[1][l0], &b.ti[2][l0], pz, cti);
    rows3_cols(&b.tj[0][l0], &b.tj[1][l0], &b.tj[2][l0], mz, ctj);
    const int m = n - l0 < 4 ? n - l0 : 4;
    for (int k = 0; k < m; k++) {
      const int l = l0 + k;
      const int il = b.i[l];
      if (il != i) {
        store3_avx2(fip, fi);
        store3_avx2(tip, ti);
        i = il;
        fip = f + 3 * (std::ptrdiff_t) i;
        tip = torque + 3 * (std::ptrdiff_t) i;
        fi = load3_avx2(fip);
        ti = load3_avx2(tip);
      }
      fi = _mm256_add_pd(fi, cf[k]);
      ti = _mm256_add_pd(ti, cti[k]);
      const int j = b.j[l];
      if (NEWTON || j < nlocal) {
        const std::ptrdiff_t j3 = 3 * (std::ptrdiff_t) j;
        if (__builtin_expect(j < jlast, 1)) {
          _mm256_storeu_pd(f + j3, _mm256_sub_pd(_mm256_loadu_pd(f + j3), cf[k]));
          _mm256_storeu_pd(torque + j3, _mm256_add_pd(_mm256_loadu_pd(torque + j3), ctj[k]));
        } else {
          store3_avx2(f + j3, _mm256_sub_pd(load3_avx2(f + j3), cf[k]));
          store3_avx2(torque + j3, _mm256_add_pd(load3_avx2(torque + j3), ctj[k]));
        }
      }
    }
  }
  store3_avx2(fip, fi);
  store3_avx2(tip, ti);
}
#endif

// the AVX2 transposes for the histories of 3 and 6 doubles (twisting's 4 and 7: scalar)
template <int NH> inline void hist_rows(Batch &b, int n, bool avx2)
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  if constexpr (NH == 3 || NH == 6)
    if (avx2) return hist_rows_avx2<NH>(b, n);
#endif
  hist_rows_scalar<NH>(b, 0, n);
}

template <int NH> inline void rows_hist(Batch &b, int n, bool avx2)
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  if constexpr (NH == 3 || NH == 6)
    if (avx2) return rows_hist_avx2<NH>(b, n);
#endif
  rows_hist_scalar<NH>(b, 0, n);
}

}    // namespace moves
}    // namespace tbags
#endif
