/* T-BAGS DEM toolkit: the chain of the contact law's stages (contact_law.h), written once, over
   lanes: one contact (compute(): the plate fix, the pair's single(), tests) or a batch of them
   (the pair's kernel: one contact per SIMD lane). Pure header, no LAMMPS types;
   tests/unit/test_contact_chain.cpp checks the batch against the stages chained by hand, bit
   for bit, in every variant.

   The stages, in order: (1) geometry and Hertz force, (2) normal damping, (3) tangential
   history, (4) tangential force, (5) rolling history, (6) rolling force. They run as five loops over the lanes
   rather than one, so that each loop keeps few values live (no register spills) and the
   compiler vectorises it ("#pragma omp simd" with -fopenmp-simd). Neither the baseline nor the
   AVX2 build contracts to FMA: a lane gives the bits of a single contact.
*/
#ifndef TBAGS_LAW_CONTACT_CHAIN_H
#define TBAGS_LAW_CONTACT_CHAIN_H

#include "contact_law.h"
#include "lanes.h"

namespace tbags {
namespace contact {

// Up to W contacts, one column each. In: i, j (the pair's atom indices, for the scatter), hist
// (where each contact's history lives), p (constants per contact unless one set serves all),
// dx = x_i - x_j (a plate: from its contact point to x_i), radii (a plate's: 0), masses
// (negative: frozen, see effective_frozen()) or, for one contact (W = 1), m* and R* given in
// meff and reff, special-bond factor, relative velocity vr = v_i - v_j, angular velocities,
// history rows h (3, or 6 with EPSD).
// Out: f (on i; j gets -f), torques ti and tj, h updated; for one contact also the normal
// force fn, fne, delta, and fs, fr, r below. The rest carries values from one loop to the next.
template <int W> struct alignas(64) Lanes {
  static constexpr int N = W;
  static constexpr bool ONE = W == 1;    // one contact: m* and R* given, the parts kept
  int i[N], j[N];
  double *hist[N];
  const Params *p[N];
  double dx[3][N], radi[N], radj[N], mi[N], mj[N], factor[N];
  double vr[3][N], wi[3][N], wj[3][N], h[6][N];
  double f[3][N], ti[3][N], tj[3][N];
  // from the normal loop to the tangential and rolling loops
  double n[3][N], vt[3][N], a[N], sqma[N], fn[N], delta[N], reff[N], rroll[N];
  double meff[N], fne[N], vnnr[N];    // from the geometry loop to the normal force
  // one contact's parts (Result): tangential force, rolling pseudo-force, centre distance
  double fs[3][N], fr[3][N], r[N];
  // one contact's implicit damping (Contact::hm > 0, else unused): the predicted relative
  // velocity and angular velocity of i (a plate's is wj), hm; the predicted normal and
  // tangential contact-point velocities (from the geometry loop)
  double vrd[3][N], wid[3][N], hm[N], vnd[N], vtd[3][N];
};
using Batch = Lanes<32>;    // the pair's: 32 contacts (64 took 2 % longer)

// The law over contacts 0..n-1 of the lanes.
//   ROLL     the rolling model of every contact (Rolling)
//   UPDATE   integrate the histories (false in a run's setup)
//   SAME     one set of constants, *same, for all contacts, with rolling on for all (mu_r > 0)
//            unless ROLL is ROLLING_NONE; else b.p per contact
//   SPECIAL  scale force and torques by b.factor (special bonds); never with SAME
//   FAST     the history rotation by its series only (tangential_history<FAST>): returns true
//            when a contact needed the exact rotation; the caller must then run the batch again
//            without FAST from the old history rows. When it returns false, all is the law's.
// clip: limit_damping; wall: the contacts are with a plate (torque arm r_i, not r_i - d/2).
template <int ROLL, bool UPDATE, bool SAME, bool SPECIAL, bool FAST, int W>
TBAGS_INLINE bool batch_law(Lanes<W> &b, int n, double dt, bool clip, const Params *same,
                            bool wall = false)
{
  using vec::V3;
  // 64 bits like the lanes: a 32-bit flag makes the vectoriser take 8 lanes (and spill)
  long long redo = 0;
  // loop 1: geometry and Hertz force (stage 1)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    double meff, reff;
    if (Lanes<W>::ONE) {
      meff = b.meff[l];
      reff = b.reff[l];
    } else {
      effective_frozen(b.mi[l], b.mj[l], b.radi[l], b.radj[l], meff, reff);
    }
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
    b.rroll[l] = rolling_radius(p, reff, b.radi[l], b.radj[l], wall);
    if constexpr (Lanes<W>::ONE) {
      b.r[l] = o.r;
      double vnd = vnnr;
      V3 vtd = vt;
      if (b.hm[l] > 0.0)
        contact_velocity(nv, b.radi[l], b.radj[l], row3(b.vrd, l), row3(b.wid, l),
                         row3(b.wj, l), vnd, vtd);
      b.vnd[l] = vnd;
      set_row3(b.vtd, l, vtd);
    }
  }
  // loop 2: normal damping (stage 2; its square root here, where the divider has time) and
  // tangential history (stage 3)
  TBAGS_PRAGMA_SIMD_OR_REDO
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    double sqma, vnnr = b.vnnr[l];
    if constexpr (Lanes<W>::ONE) {    // implicit damping: the end of the step's normal velocity
      if (b.hm[l] > 0.0)
        vnnr = implicit_velocity(b.vnd[l], b.fne[l], p.cn * std::sqrt(b.meff[l] * b.a[l]),
                                 b.hm[l]);
    }
    const double fn = normal_force(p, clip, b.meff[l], b.a[l], b.fne[l], vnnr, sqma);
    b.sqma[l] = sqma;
    b.fn[l] = fn;
    if (UPDATE) {
      V3 ht = row3(b.h, l);
      redo |= tangential_history<FAST>(p, row3(b.n, l), row3(b.vt, l), b.a[l], fn, dt, ht);
      set_row3(b.h, l, ht);
    }
  }
  // loop 3: tangential force (stage 4; torques without rolling)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    V3 ht = row3(b.h, l);
    V3 vt = row3(b.vt, l);
    if constexpr (Lanes<W>::ONE) {    // implicit damping: the end of the step's tangential velocity
      if (b.hm[l] > 0.0)
        vt = implicit_velocity(row3(b.vtd, l), (-p.kt * b.a[l]) * ht, p.ct * b.sqma[l],
                               TANGENTIAL_COMPLIANCE * b.hm[l]);
    }
    LaneOut o;
    tangential_force(p, row3(b.n, l), vt, b.a[l], b.sqma[l], b.fn[l], b.delta[l], b.radi[l],
                     b.radj[l], wall, ht, o);
    set_row3(b.h, l, ht);
    if (Lanes<W>::ONE) set_row3(b.fs, l, o.fs);
    const double fl = SPECIAL ? b.factor[l] : 1.0;
    set_row3(b.f, l, fl * o.f);
    if constexpr (ROLL == ROLLING_NONE) {
      set_row3(b.ti, l, fl * o.ti);
      set_row3(b.tj, l, fl * o.tj);
    } else {    // the rolling loop adds its torque first, then applies the factor
      set_row3(b.ti, l, o.ti);
      set_row3(b.tj, l, o.tj);
    }
  }
  if (ROLL == ROLLING_NONE) return redo != 0;
  // loop 4: rolling history (stage 5, EPSD)
  if (ROLL == ROLLING_EPSD && UPDATE) {
    TBAGS_PRAGMA_SIMD_OR_REDO
    for (int l = 0; l < n; l++) {
      const Params &p = SAME ? *same : *b.p[l];
      V3 hr = row3(b.h + 3, l);
      redo |= rolling_history<SAME, FAST>(p, row3(b.n, l), b.a[l], std::fabs(b.fn[l]),
                                          b.rroll[l], row3(b.wi, l), row3(b.wj, l), dt, hr);
      set_row3(b.h + 3, l, hr);
    }
  }
  // loop 5: rolling force and torque (stage 6)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    V3 hr{0.0, 0.0, 0.0};
    if constexpr (ROLL == ROLLING_EPSD) hr = row3(b.h + 3, l);
    V3 fr, troll;
    bool on;
    rolling_force<ROLL, SAME>(p, row3(b.n, l), b.a[l], std::fabs(b.fn[l]), b.rroll[l],
                              row3(b.wi, l), row3(b.wj, l), hr, fr, troll, on);
    if (ROLL == ROLLING_EPSD) set_row3(b.h + 3, l, hr);
    if (Lanes<W>::ONE) set_row3(b.fr, l, fr);
    const V3 ti = row3(b.ti, l), tj = row3(b.tj, l);
    const double fl = SPECIAL ? b.factor[l] : 1.0;
    set_row3(b.ti, l, fl * vec::select(on, ti + troll, ti));
    set_row3(b.tj, l, fl * vec::select(on, tj - troll, tj));
  }
  return redo != 0;
}

// One contact (the plate fix, the pair's single(), tests), rolling model fixed at compile
// time: the chain over one lane. hist: 3 (or 6 for EPSD) doubles, integrated when update.
template <int ROLL>
TBAGS_INLINE void compute_t(const Params &p, const Contact &c, double *hist, bool update, Result &o)
{
  using namespace vec;
  Lanes<1> b;
  b.p[0] = &p;
  set_row3(b.dx, 0, load3(c.dx));
  b.radi[0] = c.radi;
  b.radj[0] = c.radj;
  b.meff[0] = c.meff;
  b.reff[0] = c.reff;
  set_row3(b.vr, 0, load3(c.vi) - load3(c.vj));
  set_row3(b.wi, 0, load3(c.wi));
  set_row3(b.wj, 0, load3(c.wj));
  set_row3(b.h, 0, load3(hist));
  set_row3(b.h + 3, 0, ROLL == ROLLING_EPSD ? load3(hist + 3) : V3{0.0, 0.0, 0.0});
  set_row3(b.fr, 0, V3{0.0, 0.0, 0.0});    // no rolling: the chain leaves it
  const bool implicit = c.hm > 0.0;    // damping against the end of the step's velocities
  b.hm[0] = c.hm;
  set_row3(b.vrd, 0, load3(implicit ? c.vdi : c.vi) - load3(c.vj));
  set_row3(b.wid, 0, load3(implicit ? c.wdi : c.wi));
  if (update)
    batch_law<ROLL, true, false, false, false>(b, 1, c.dt, p.limit_damping, nullptr, c.wall);
  else
    batch_law<ROLL, false, false, false, false>(b, 1, c.dt, p.limit_damping, nullptr, c.wall);
  store3(row3(b.h, 0), hist);
  if (ROLL == ROLLING_EPSD) store3(row3(b.h + 3, 0), hist + 3);
  store3(row3(b.f, 0), o.f);
  store3(row3(b.ti, 0), o.ti);
  store3(row3(b.tj, 0), o.tj);
  store3(row3(b.fs, 0), o.fs);
  store3(row3(b.fr, 0), o.fr);
  o.fn = b.fn[0];
  o.fne = b.fne[0];
  o.delta = b.delta[0];
  o.r = b.r[0];
}

// One contact, rolling model from the parameters.
inline void compute(const Params &p, const Contact &c, double *hist, bool update, Result &o)
{
  if (p.rolling == ROLLING_EPSD) compute_t<ROLLING_EPSD>(p, c, hist, update, o);
  else if (p.rolling == ROLLING_CDT) compute_t<ROLLING_CDT>(p, c, hist, update, o);
  else compute_t<ROLLING_NONE>(p, c, hist, update, o);
}

}    // namespace contact
}    // namespace tbags
#endif
