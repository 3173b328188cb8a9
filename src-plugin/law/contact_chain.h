/* T-BAGS DEM toolkit: the chain of the contact law's stages (contact_law.h), written once, over
   lanes: one contact (compute(): the plate fix, the pair's single(), tests) or a batch of them
   (the pair's kernel: one contact per SIMD lane). Pure header, no LAMMPS types;
   tests/unit/test_contact_chain.cpp checks the batch against the stages chained by hand, bit
   for bit, in every variant.

   The stages, in order: (1) geometry and Hertz force, (2) normal force, (3) tangential
   history, (4) tangential force, (5) rolling history, (6) rolling force, (7) twisting (where
   asked); the damping a sub-model (explicit, or implicit for the plate fix). They run as loops
   over the lanes
   rather than one, so that each loop keeps few values live (no register spills) and the
   compiler vectorises it (lanes.h's pragma); the State goes from one loop to the next in the
   lanes' rows. Neither the baseline nor the AVX2 build contracts to FMA: a lane gives the bits
   of a single contact.
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
// history rows h (tangential 3, then EPSD's 3, then the twist angle: twist_row()).
// Out: f (on i; j gets -f), torques ti and tj, h updated; for one contact also the State
// (fn, fne, delta, r) and fs, fr below. The state's rows carry it from one loop to the next.
template <int W> struct alignas(64) Lanes {
  static constexpr int N = W;
  static constexpr bool ONE = W == 1;    // one contact: m* and R* given, the parts kept
  int i[N], j[N];
  double *hist[N];
  const Params *p[N];
  double dx[3][N], radi[N], radj[N], mi[N], mj[N], factor[N];
  double vr[3][N], wi[3][N], wj[3][N], h[7][N];
  double f[3][N], ti[3][N], tj[3][N];
  // the State, row by row (lane_state())
  double n[3][N], vt[3][N], vroll[3][N], wt[N], vn[N], r[N], delta[N], a[N], meff[N], rr[N],
      fne[N], fn[N], sqma[N];
  double reff[N];    // one contact's R* (given)
  // one contact's parts (Result): tangential force, rolling pseudo-force
  double fs[3][N], fr[3][N];
  // one contact's implicit damping (ImplicitDamping): the predicted relative velocity and
  // angular velocity of i (a plate's is wj), hm; the predicted normal and tangential
  // contact-point velocities (from the geometry loop)
  double vrd[3][N], wid[3][N], hm[N], vnd[N], vtd[3][N];
};
using Batch = Lanes<32>;    // the pair's: 32 contacts (64 took 2 % longer)

// the history's layout per contact: tangential displacement (3), the rolling model's (EPSD: 3),
// then the twist angle (TWIST: 1)
constexpr int twist_row(int rolling) { return 3 + (rolling == ROLLING_EPSD ? EpsdRolling::HISTORY : 0); }
constexpr int history_size(int rolling, bool twist) { return twist_row(rolling) + (twist ? 1 : 0); }

// lane l's State from its rows (the geometry loop writes them, normal_force's loop fn and sqma)
template <int W> TBAGS_INLINE State lane_state(const Lanes<W> &b, int l)
{
  State s;
  s.n = row3(b.n, l);
  s.vt = row3(b.vt, l);
  s.vroll = row3(b.vroll, l);
  s.wt = b.wt[l];
  s.vn = b.vn[l];
  s.r = b.r[l];
  s.delta = b.delta[l];
  s.a = b.a[l];
  s.meff = b.meff[l];
  s.rr = b.rr[l];
  s.fne = b.fne[l];
  s.fn = b.fn[l];
  s.sqma = b.sqma[l];
  return s;
}
// lane l's Touch (m* and R* from the masses, the frozen-particle rule; one contact: given)
template <int W> TBAGS_INLINE Touch lane_touch(const Lanes<W> &b, int l)
{
  Touch t;
  t.dx = row3(b.dx, l);
  t.vr = row3(b.vr, l);
  t.wi = row3(b.wi, l);
  t.wj = row3(b.wj, l);
  t.radi = b.radi[l];
  t.radj = b.radj[l];
  if (Lanes<W>::ONE) {
    t.meff = b.meff[l];
    t.reff = b.reff[l];
  } else {
    effective_frozen(b.mi[l], b.mj[l], b.radi[l], b.radj[l], t.meff, t.reff);
  }
  return t;
}

// The normal and tangential damping over the lanes, as two sub-models of the chain: explicit
// (against the half step's velocities, as stock: the state's own) and implicit (one contact of
// the plate fix with Contact::hm > 0: against the end of the step's velocities, predicted from
// i's velocities b.vrd, b.wid in the geometry loop; implicit_normal(), implicit_tangential()).
struct ExplicitDamping {
  template <int W> static TBAGS_INLINE void predict(Lanes<W> &, int, const State &, const Touch &) {}
  template <int W> static TBAGS_INLINE void normal(const Params &, const Lanes<W> &, int, State &) {}
  template <int W>
  static TBAGS_INLINE void tangential(const Params &, const Lanes<W> &, int, const vec::V3 &, State &)
  {
  }
};
struct ImplicitDamping {
  template <int W>
  static TBAGS_INLINE void predict(Lanes<W> &b, int l, const State &s, const Touch &t)
  {
    Touch q = t;    // i's predicted velocities
    q.vr = row3(b.vrd, l);
    q.wi = row3(b.wid, l);
    double vn;
    vec::V3 vt;
    contact_velocity(s.n, q, vn, vt);
    b.vnd[l] = vn;
    set_row3(b.vtd, l, vt);
  }
  template <int W> static TBAGS_INLINE Predicted predicted(const Lanes<W> &b, int l)
  {
    return Predicted{b.vnd[l], row3(b.vtd, l), b.hm[l]};
  }
  template <int W>
  static TBAGS_INLINE void normal(const Params &p, const Lanes<W> &b, int l, State &s)
  {
    implicit_normal(p, predicted(b, l), s);
  }
  template <int W>
  static TBAGS_INLINE void tangential(const Params &p, const Lanes<W> &b, int l, const vec::V3 &ht,
                                      State &s)
  {
    implicit_tangential(p, predicted(b, l), ht, s);
  }
};

// The law over contacts 0..n-1 of the lanes: the stages of contact_law.h, one loop each or two.
//   ROLL     the rolling model of every contact (Rolling)
//   UPDATE   integrate the histories (false in a run's setup)
//   SAME     one set of constants, *same, for all contacts, with rolling on for all (mu_r > 0)
//            unless ROLL is ROLLING_NONE; else b.p per contact
//   SPECIAL  scale force and torques by b.factor (special bonds); never with SAME
//   FAST     the history rotation by its series only (tangential_history<FAST>): returns true
//            when a contact needed the exact rotation; the caller must then run the batch again
//            without FAST from the old history rows. When it returns false, all is the law's.
//   Damping  ExplicitDamping or (one contact of the plate fix) ImplicitDamping
//   TWIST    the twisting resistance (TwistingSds) where p.ktw > 0, history row twist_row(ROLL)
// clip: limit_damping; wall: the contacts are with a plate (torque arm r_i, not r_i - d/2).
template <int ROLL, bool UPDATE, bool SAME, bool SPECIAL, bool FAST,
          class Damping = ExplicitDamping, bool TWIST = false, int W>
TBAGS_INLINE bool batch_law(Lanes<W> &b, int n, double dt, bool clip, const Params *same,
                            bool wall = false)
{
  using vec::V3;
  using Rolling = typename RollingModel<ROLL>::type;
  constexpr bool ONE = Lanes<W>::ONE;
  // the special-bond factor scales the torques once all are summed: in the last loop that adds one
  constexpr bool LAST_ROLL = ROLL != ROLLING_NONE && !TWIST;
  constexpr bool LAST_TANG = ROLL == ROLLING_NONE && !TWIST;
  constexpr int TW = twist_row(ROLL);
  // 64 bits like the lanes: a 32-bit flag makes the vectoriser take 8 lanes (and spill)
  long long redo = 0;
  // loop 1: geometry and Hertz force (stage 1)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    const Touch t = lane_touch(b, l);
    const State s = geometry(p, t, wall);
    set_row3(b.n, l, s.n);
    set_row3(b.vt, l, s.vt);
    if (ROLL != ROLLING_NONE) set_row3(b.vroll, l, s.vroll);
    if (TWIST) b.wt[l] = s.wt;
    b.vn[l] = s.vn;
    b.delta[l] = s.delta;
    b.a[l] = s.a;
    b.meff[l] = s.meff;
    b.rr[l] = s.rr;
    b.fne[l] = s.fne;
    if (ONE) b.r[l] = s.r;
    Damping::predict(b, l, s, t);
  }
  // loop 2: normal force (stage 2; its square root here, where the divider has time) and
  // tangential history (stage 3)
  TBAGS_PRAGMA_SIMD_OR_REDO
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    State s = lane_state(b, l);
    Damping::normal(p, b, l, s);
    normal_force(p, clip, s);
    b.sqma[l] = s.sqma;
    b.fn[l] = s.fn;
    if (UPDATE) {
      V3 ht = row3(b.h, l);
      redo |= tangential_history<FAST>(p, s, dt, ht);
      set_row3(b.h, l, ht);
    }
  }
  // loop 3: tangential force (stage 4), force and torques (rolling's added below)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const Params &p = SAME ? *same : *b.p[l];
    State s = lane_state(b, l);
    V3 ht = row3(b.h, l);
    Damping::tangential(p, b, l, ht, s);
    const V3 fs = tangential_force(p, s, ht);
    set_row3(b.h, l, ht);
    if (ONE) set_row3(b.fs, l, fs);
    const Forces o = contact_forces(s, fs, b.radi[l], b.radj[l], wall);
    const double fl = SPECIAL ? b.factor[l] : 1.0;
    set_row3(b.f, l, fl * o.f);
    if constexpr (LAST_TANG) {
      set_row3(b.ti, l, fl * o.ti);
      set_row3(b.tj, l, fl * o.tj);
    } else {    // the rolling or twisting loop adds its torque first, then applies the factor
      set_row3(b.ti, l, o.ti);
      set_row3(b.tj, l, o.tj);
    }
  }
  if constexpr (ROLL != ROLLING_NONE) {
    // loop 4: rolling history (stage 5)
    if constexpr (Rolling::HISTORY > 0 && UPDATE) {
      TBAGS_PRAGMA_SIMD_OR_REDO
      for (int l = 0; l < n; l++) {
        const Params &p = SAME ? *same : *b.p[l];
        const State s = lane_state(b, l);
        V3 hr = row3(b.h + 3, l);
        redo |= Rolling::template history<SAME, FAST>(p, s, dt, hr);
        set_row3(b.h + 3, l, hr);
      }
    }
    // loop 5: rolling force and torque (stage 6)
    TBAGS_PRAGMA_SIMD
    for (int l = 0; l < n; l++) {
      const Params &p = SAME ? *same : *b.p[l];
      const State s = lane_state(b, l);
      V3 hr{0.0, 0.0, 0.0};
      if constexpr (Rolling::HISTORY > 0) hr = row3(b.h + 3, l);
      const V3 fr = Rolling::template force<SAME>(p, s, hr);
      if constexpr (Rolling::HISTORY > 0) set_row3(b.h + 3, l, hr);
      if (ONE) set_row3(b.fr, l, fr);
      const bool on = rolling_acts<SAME>(p);
      const V3 troll = rolling_torque(s, fr);
      const V3 ti = row3(b.ti, l), tj = row3(b.tj, l);
      const double fl = (SPECIAL && LAST_ROLL) ? b.factor[l] : 1.0;
      set_row3(b.ti, l, fl * vec::select(on, ti + troll, ti));
      set_row3(b.tj, l, fl * vec::select(on, tj - troll, tj));
    }
  }
  if constexpr (TWIST) {
    // loop 6: twisting history and moment (stage 7), its torque added, then the factor
    TBAGS_PRAGMA_SIMD
    for (int l = 0; l < n; l++) {
      const Params &p = SAME ? *same : *b.p[l];
      const State s = lane_state(b, l);
      double theta = b.h[TW][l];
      if (UPDATE) TwistingSds::history(p, s, dt, theta);
      const V3 ttw = twisting_torque(s, TwistingSds::moment(p, s, theta));
      b.h[TW][l] = theta;
      const double fl = SPECIAL ? b.factor[l] : 1.0;
      set_row3(b.ti, l, fl * (row3(b.ti, l) + ttw));
      set_row3(b.tj, l, fl * (row3(b.tj, l) - ttw));
    }
  }
  return redo != 0;
}

// One contact (the plate fix, the pair's single(), tests), rolling model and twisting fixed at
// compile time: the chain over one lane. hist: history_size(ROLL, TWIST) doubles, integrated
// when update.
template <int ROLL, bool TWIST = false>
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
  constexpr int TW = twist_row(ROLL);
  if (TWIST) b.h[TW][0] = hist[TW];
  set_row3(b.fr, 0, V3{0.0, 0.0, 0.0});    // no rolling: the chain leaves it
  set_row3(b.vroll, 0, V3{0.0, 0.0, 0.0});
  b.wt[0] = 0.0;    // no twisting: the geometry loop leaves it (lane_state() reads it)
  b.fn[0] = b.sqma[0] = 0.0;
  const bool implicit = c.hm > 0.0;    // damping against the end of the step's velocities
  if (implicit) {
    b.hm[0] = c.hm;
    set_row3(b.vrd, 0, load3(c.vdi) - load3(c.vj));
    set_row3(b.wid, 0, load3(c.wdi));
    if (update) batch_law<ROLL, true, false, false, false, ImplicitDamping, TWIST>(b, 1, c.dt, p.limit_damping, nullptr, c.wall);
    else batch_law<ROLL, false, false, false, false, ImplicitDamping, TWIST>(b, 1, c.dt, p.limit_damping, nullptr, c.wall);
  } else {
    if (update) batch_law<ROLL, true, false, false, false, ExplicitDamping, TWIST>(b, 1, c.dt, p.limit_damping, nullptr, c.wall);
    else batch_law<ROLL, false, false, false, false, ExplicitDamping, TWIST>(b, 1, c.dt, p.limit_damping, nullptr, c.wall);
  }
  store3(row3(b.h, 0), hist);
  if (ROLL == ROLLING_EPSD) store3(row3(b.h + 3, 0), hist + 3);
  if (TWIST) hist[TW] = b.h[TW][0];
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

// One contact, rolling model and twisting from the parameters (twisting where p.ktw > 0: hist
// then holds history_size(p.rolling, true) doubles).
template <bool TWIST>
inline void compute_twist(const Params &p, const Contact &c, double *hist, bool update, Result &o)
{
  if (p.rolling == ROLLING_EPSD) compute_t<ROLLING_EPSD, TWIST>(p, c, hist, update, o);
  else if (p.rolling == ROLLING_CDT) compute_t<ROLLING_CDT, TWIST>(p, c, hist, update, o);
  else compute_t<ROLLING_NONE, TWIST>(p, c, hist, update, o);
}
inline void compute(const Params &p, const Contact &c, double *hist, bool update, Result &o)
{
  if (p.ktw > 0.0) compute_twist<true>(p, c, hist, update, o);
  else compute_twist<false>(p, c, hist, update, o);
}

}    // namespace contact
}    // namespace tbags
#endif
