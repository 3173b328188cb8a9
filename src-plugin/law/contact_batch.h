/* T-BAGS DEM toolkit: the contact law of contact_law.h over a batch of contacts, one contact per
   SIMD lane. Pure header, no LAMMPS types: the pair style gathers touching pairs into a Batch
   (structure of arrays: one row per value, one column per contact), calls batch_law() and
   scatters the rows back; tests/unit/test_contact_batch.cpp checks it against contact_lane()
   bit for bit.

   The stages are those of contact_lane() (geometry, normal force, tangential history, tangential
   force, rolling history, rolling force), called in the same order on the same values; they run
   as five loops rather than one, so that each loop keeps few values live (no register spills)
   and the compiler vectorises it ("#pragma omp simd" with -fopenmp-simd). Neither the baseline
   nor the AVX2 build contracts to FMA: the lanes give the scalar law's bits.
*/
#ifndef TBAGS_LAW_CONTACT_BATCH_H
#define TBAGS_LAW_CONTACT_BATCH_H

#include "contact_law.h"

#if defined(_OPENMP) || defined(TBAGS_OPENMP_SIMD)
#define TBAGS_PRAGMA_SIMD _Pragma("omp simd")
#define TBAGS_PRAGMA_SIMD_OR_REDO _Pragma("omp simd reduction(| : redo)")
#else
#define TBAGS_PRAGMA_SIMD
#define TBAGS_PRAGMA_SIMD_OR_REDO
#endif

namespace tbags {
namespace contact {

// Up to N contacts, one column each. In: i, j (the pair's atom indices, for the scatter), hist
// (where each contact's history lives), p (constants per contact unless one set serves all),
// dx = x_i - x_j, radii, masses (negative: frozen, see effective_frozen()), special-bond factor,
// relative velocity vr = v_i - v_j, angular velocities, history rows h (3, or 6 with EPSD).
// Out: f (on i; j gets -f), torques ti and tj, h updated. The rest carries values from one
// loop of batch_law() to the next.
struct alignas(64) Batch {
  static constexpr int N = 32;
  int i[N], j[N];
  double *hist[N];
  const Params *p[N];
  double dx[3][N], radi[N], radj[N], mi[N], mj[N], factor[N];
  double vr[3][N], wi[3][N], wj[3][N], h[6][N];
  double f[3][N], ti[3][N], tj[3][N];
  // from the normal loop to the tangential and rolling loops
  double n[3][N], vt[3][N], a[N], sqma[N], fn[N], delta[N], reff[N];
  double meff[N], fne[N], vnnr[N];    // from the geometry loop to the normal force
};

// column l of three rows (a vector's x, y, z)
TBAGS_INLINE vec::V3 row3(const double (*r)[Batch::N], int l) { return vec::V3{r[0][l], r[1][l], r[2][l]}; }
TBAGS_INLINE void set_row3(double (*r)[Batch::N], int l, const vec::V3 &v)
{
  r[0][l] = v.x;
  r[1][l] = v.y;
  r[2][l] = v.z;
}

// The law over contacts 0..n-1 of the batch.
//   ROLL     the rolling model of every contact (Rolling)
//   UPDATE   integrate the histories (false in a run's setup)
//   SAME     one set of constants, *same, for all contacts, with rolling on for all (mu_r > 0)
//            unless ROLL is ROLLING_NONE; else b.p per contact
//   SPECIAL  scale force and torques by b.factor (special bonds); never with SAME
//   FAST     the history rotation by its series only (tangential_history<FAST>): returns true
//            when a contact needed the exact rotation; the caller must then run the batch again
//            without FAST from the old history rows. When it returns false, all is the law's.
template <int ROLL, bool UPDATE, bool SAME, bool SPECIAL, bool FAST>
TBAGS_INLINE bool batch_law(Batch &b, int n, double dt, bool clip, const Params *same)
{
  using vec::V3;
  // 64 bits like the lanes: a 32-bit flag makes the vectoriser take 8 lanes (and spill)
  long long redo = 0;
  // 1. geometry and Hertz force
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    double meff, reff;
    effective_frozen(b.mi[l], b.mj[l], b.radi[l], b.radj[l], meff, reff);
    // r^2 and r_i + r_j as in the gather (same operations, same bits)
    const double dx0 = b.dx[0][l], dx1 = b.dx[1][l], dx2 = b.dx[2][l];
    const double rsq = dx0 * dx0 + dx1 * dx1 + dx2 * dx2;
    LaneOut o;
    V3 nv, vt;
    double vnnr, a;
    contact_geometry(p, V3{dx0, dx1, dx2}, rsq, b.radi[l] + b.radj[l], reff, b.radi[l],
                     b.radj[l], row3(b.vr, l), row3(b.wi, l), row3(b.wj, l), o, nv, vnnr, vt, a);
    set_row3(b.n, l, nv);
    set_row3(b.vt, l, vt);
    b.a[l] = a;
    b.meff[l] = meff;
    b.fne[l] = o.fne;
    b.vnnr[l] = vnnr;
    b.delta[l] = o.delta;
    b.reff[l] = reff;
  }
  // 2. normal damping (its square root here, where the divider has time) and tangential history
  TBAGS_PRAGMA_SIMD_OR_REDO
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    double sqma;
    const double fn = normal_force(p, clip, b.meff[l], b.a[l], b.fne[l], b.vnnr[l], sqma);
    b.sqma[l] = sqma;
    b.fn[l] = fn;
    if (UPDATE) {
      V3 ht = row3(b.h, l);
      redo |= tangential_history<FAST>(p, row3(b.n, l), row3(b.vt, l), b.a[l], fn, dt, ht);
      set_row3(b.h, l, ht);
    }
  }
  // 3. tangential force (torques without rolling)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    V3 ht = row3(b.h, l);
    LaneOut o;
    tangential_force(p, row3(b.n, l), row3(b.vt, l), b.a[l], b.sqma[l], b.fn[l], b.delta[l],
                     b.radi[l], b.radj[l], false, ht, o);
    set_row3(b.h, l, ht);
    const double fl = SPECIAL ? b.factor[l] : 1.0;
    set_row3(b.f, l, fl * o.f);
    // with rolling, its loop adds its torque first, then applies the factor
    set_row3(b.ti, l, ROLL == ROLLING_NONE ? fl * o.ti : o.ti);
    set_row3(b.tj, l, ROLL == ROLLING_NONE ? fl * o.tj : o.tj);
  }
  if (ROLL == ROLLING_NONE) return redo != 0;
  // 4. rolling history (EPSD)
  if (ROLL == ROLLING_EPSD && UPDATE) {
    TBAGS_PRAGMA_SIMD_OR_REDO
    for (int l = 0; l < n; l++) {
      const Params &p = SAME ? *same : *b.p[l];
      V3 hr = row3(b.h + 3, l);
      redo |= rolling_history<SAME, FAST>(p, row3(b.n, l), b.a[l], std::fabs(b.fn[l]),
                                          b.reff[l], row3(b.wi, l), row3(b.wj, l), dt, hr);
      set_row3(b.h + 3, l, hr);
    }
  }
  // 5. rolling force and torque
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    V3 hr = ROLL == ROLLING_EPSD ? row3(b.h + 3, l) : V3{0.0, 0.0, 0.0};
    V3 fr, troll;
    bool on;
    rolling_force<ROLL, SAME>(p, row3(b.n, l), b.a[l], std::fabs(b.fn[l]), b.reff[l],
                              row3(b.wi, l), row3(b.wj, l), hr, fr, troll, on);
    if (ROLL == ROLLING_EPSD) set_row3(b.h + 3, l, hr);
    const V3 ti = row3(b.ti, l), tj = row3(b.tj, l);
    const double fl = SPECIAL ? b.factor[l] : 1.0;
    set_row3(b.ti, l, fl * vec::select(on, ti + troll, ti));
    set_row3(b.tj, l, fl * vec::select(on, tj - troll, tj));
  }
  return redo != 0;
}

}    // namespace contact
}    // namespace tbags
#endif
