/* T-BAGS DEM toolkit: the yarn bond law's stages (yarn_law.h) chained once, over lanes: one
   bond (compute(): single(), tests) or a batch of bonds of one type (bond_style bpm/yarn: one
   bond per SIMD lane). Pure header, no LAMMPS types; tests/unit/test_yarn_chain.cpp checks the
   batch against the stages chained by hand, bit for bit.

   Three loops over the lanes: kinematics and history (vectorised), the axial force (a table
   look-up per bond), the forces (vectorised). Neither the baseline nor the AVX2 build
   contracts to FMA, so a lane gives the bits of a single bond.
*/
#ifndef TBAGS_LAW_YARN_CHAIN_H
#define TBAGS_LAW_YARN_CHAIN_H

#include "lanes.h"
#include "yarn_law.h"

namespace tbags {
namespace yarn {

// Up to W bonds of one type, one column each. In: the ends' positions x, velocities v and
// angular velocities w (i: the end of the lower tag), the history rows h (NHISTORY, h[R0] > 0).
// Out: f (on i; j gets -f), torques ti and tj, strain eps, axial force fax, length r, broken;
// h updated when integrating. The rest carries values between the loops.
template <int W> struct alignas(64) Lanes {
  static constexpr int N = W;
  double xi[3][N], xj[3][N], vi[3][N], vj[3][N], wi[3][N], wj[3][N];
  double h[NHISTORY][N];
  double f[3][N], ti[3][N], tj[3][N], eps[N], fax[N], r[N];
  long long broken[N];    // 64 bits like the lanes (a 1-byte flag keeps the AVX2 loop scalar)
  double n[3][N], vs[3][N], wrel[3][N], vn[N];
};
using Batch = Lanes<32>;    // bond_style bpm/yarn's (14 KB, in L1)

// The law over bonds 0..n-1 of the lanes, all with the constants p. UPDATE: integrate the
// histories (false in a run's set-up, single() and outputs).
template <bool UPDATE, int W>
TBAGS_INLINE void chain(const Params &p, Lanes<W> &b, int n, double dt)
{
  using vec::V3;
  const Springs k = springs(p);
  // loop 1: kinematics (stage 1) and the incremental springs' history (stage 2)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    const double r0 = b.h[R0][l];
    const Motion m = kinematics(row3(b.xi, l), row3(b.xj, l), row3(b.vi, l), row3(b.vj, l),
                                row3(b.wi, l), row3(b.wj, l), r0);
    if (UPDATE) {
      V3 fs = row3(b.h + FS, l), mb = row3(b.h + MB, l);
      integrate(k, m, r0, dt, fs, mb, b.h[MT][l]);
      set_row3(b.h + FS, l, fs);
      set_row3(b.h + MB, l, mb);
    }
    set_row3(b.n, l, m.n);
    set_row3(b.vs, l, m.vs);
    set_row3(b.wrel, l, m.wrel);
    b.vn[l] = m.vn;
    b.r[l] = m.r;
    b.eps[l] = m.eps;
    b.broken[l] = breaks(p, m.eps);
  }
  // loop 2: the axial force (stage 3: table look-up, largest strain)
  for (int l = 0; l < n; l++) b.fax[l] = axial_force(p, b.eps[l], &b.h[EPSMAX][l], UPDATE);
  // loop 3: forces and torques (stage 4)
  TBAGS_PRAGMA_SIMD
  for (int l = 0; l < n; l++) {
    Motion m;
    m.n = row3(b.n, l);
    m.vs = row3(b.vs, l);
    m.wrel = row3(b.wrel, l);
    m.r = b.r[l];
    m.eps = b.eps[l];
    m.vn = b.vn[l];
    V3 f, ti, tj;
    forces(p, m, b.fax[l], row3(b.h + FS, l), row3(b.h + MB, l), b.h[MT][l], f, ti, tj);
    set_row3(b.f, l, f);
    set_row3(b.ti, l, ti);
    set_row3(b.tj, l, tj);
  }
}

// one bond: its ends and time step
struct Bond {
  const double *xi, *xj, *vi, *vj, *wi, *wj;
  double dt;
};

struct Result {
  double f[3];      // force on i (j gets -f)
  double ti[3], tj[3];
  double eps, fax;  // strain and axial force (tension positive)
  double r;
  bool broken;
};

// one bond step through the chain; hist holds NHISTORY doubles (hist[R0] > 0)
inline void compute(const Params &p, const Bond &b, double *hist, bool update, Result &o)
{
  Lanes<1> l;
  for (int k = 0; k < 3; k++) {
    l.xi[k][0] = b.xi[k], l.xj[k][0] = b.xj[k];
    l.vi[k][0] = b.vi[k], l.vj[k][0] = b.vj[k];
    l.wi[k][0] = b.wi[k], l.wj[k][0] = b.wj[k];
  }
  for (int k = 0; k < NHISTORY; k++) l.h[k][0] = hist[k];
  if (update) chain<true>(p, l, 1, b.dt);
  else chain<false>(p, l, 1, b.dt);
  for (int k = 0; k < NHISTORY; k++) hist[k] = l.h[k][0];
  for (int k = 0; k < 3; k++) o.f[k] = l.f[k][0], o.ti[k] = l.ti[k][0], o.tj[k] = l.tj[k][0];
  o.eps = l.eps[0];
  o.fax = l.fax[0];
  o.r = l.r[0];
  o.broken = l.broken[0];
}

}    // namespace yarn
}    // namespace tbags
#endif
