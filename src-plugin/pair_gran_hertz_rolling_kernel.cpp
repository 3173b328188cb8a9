/* ----------------------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   pair_style gran/hertz/rolling, its compute(): the force kernel, in three passes per step.
     pass 1  pack_atoms(): positions, radii, velocities, masses and types of local and ghost
             atoms into two aligned records per atom; walk_pairs(): the candidate list (or the
             whole neighbor list, rebuilding the candidate list), the touch flags and histories
             of pairs that separate, and the touching pairs gathered into a Batch
     pass 2  the law over each full Batch (law/contact_chain.h), its history rows moved in and
             out by pair_gran_hertz_rolling_moves.h
     pass 3  forces and torques added to the atoms in neighbor-list order (scatter)
   Built for the baseline and AVX2 (simd_target.h); both give the same bits.
------------------------------------------------------------------------- */

#include "pair_gran_hertz_rolling.h"
#include "pair_gran_hertz_rolling_moves.h"

#include "atom.h"
#include "error.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
namespace law = tbags::contact;
using namespace tbags::moves;

namespace {
typedef double v4d __attribute__((vector_size(32), may_alias));    // AtomX, aligned

// the batch law, built for the baseline and for AVX2 (law::batch_law is forced inline into each)
template <int ROLL, bool UPDATE, bool SAME, bool SPECIAL, bool FAST, bool TWIST>
bool batch_law_baseline(Batch &b, int n, double dt, bool clip, const law::Params *same)
{
  return law::batch_law<ROLL, UPDATE, SAME, SPECIAL, FAST, law::ExplicitDamping, TWIST>(
      b, n, dt, clip, same);
}

#ifdef TBAGS_HAVE_AVX2_CLONE
template <int ROLL, bool UPDATE, bool SAME, bool SPECIAL, bool FAST, bool TWIST>
TBAGS_TARGET_AVX2 bool batch_law_avx2(Batch &b, int n, double dt, bool clip,
                                      const law::Params *same)
{
  return law::batch_law<ROLL, UPDATE, SAME, SPECIAL, FAST, law::ExplicitDamping, TWIST>(
      b, n, dt, clip, same);
}
#endif

// the build chosen at run time (avx2), the history integrated or not (integrate: not in a run's
// set-up, which rotates no history: there the law without FAST, one instance less); SAME,
// SPECIAL, FAST, TWIST as law::batch_law()
template <int ROLL, bool SAME, bool SPECIAL, bool FAST, bool TWIST>
bool run_law(Batch &b, int n, double dt, bool clip, bool avx2, bool integrate,
             const law::Params *same)
{
#ifdef TBAGS_HAVE_AVX2_CLONE
  if (avx2)
    return integrate ? batch_law_avx2<ROLL, true, SAME, SPECIAL, FAST, TWIST>(b, n, dt, clip, same)
                     : batch_law_avx2<ROLL, false, SAME, SPECIAL, false, TWIST>(b, n, dt, clip, same);
#endif
  return integrate ? batch_law_baseline<ROLL, true, SAME, SPECIAL, FAST, TWIST>(b, n, dt, clip, same)
                   : batch_law_baseline<ROLL, false, SAME, SPECIAL, false, TWIST>(b, n, dt, clip, same);
}
}    // namespace

void PairGranHertzRolling::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  if (!batch) batch.reset(new Batch());    // zeroed: whole 4-row groups are read
  // special-bond bits in the neighbor list: only with bonds and special factors other than 0, 1
  const bool special = atom->molecular != Atom::ATOMIC &&
      (neighbor->special_flag[1] == 2 || neighbor->special_flag[2] == 2 ||
       neighbor->special_flag[3] == 2);
  if (twisting) return eval_rolling<true>(special);
  eval_rolling<false>(special);
}

template <bool TWIST> void PairGranHertzRolling::eval_rolling(bool special)
{
  if (rolling == law::ROLLING_EPSD) special ? eval<law::ROLLING_EPSD, true, TWIST>() : eval<law::ROLLING_EPSD, false, TWIST>();
  else if (rolling == law::ROLLING_CDT) special ? eval<law::ROLLING_CDT, true, TWIST>() : eval<law::ROLLING_CDT, false, TWIST>();
  else special ? eval<law::ROLLING_NONE, true, TWIST>() : eval<law::ROLLING_NONE, false, TWIST>();
}

/* ----------------------------------------------------------------------
   the constants of all type pairs when they are all the same (e.g. pair_coeff * *), else null
------------------------------------------------------------------------- */

const law::Params *PairGranHertzRolling::uniform_params() const
{
  const law::Params &p = law[ntypes1 + 1];
  for (int i = 1; i < ntypes1; i++)
    for (int j = 1; j < ntypes1; j++) {
      const law::Params &q = law[i * ntypes1 + j];
      if (q.kn != p.kn || q.kt != p.kt || q.cn != p.cn || q.ct != p.ct || q.mu != p.mu ||
          q.mur != p.mur || q.krs != p.krs || q.rolling != p.rolling ||
          q.limit_damping != p.limit_damping || q.roll_mean != p.roll_mean || q.ktw != p.ktw ||
          q.ctw != p.ctw || q.mutw != p.mutw)
        return nullptr;
    }
  return &p;
}

/* ----------------------------------------------------------------------
   the kernel's per-atom data of local and ghost atoms, packed into two aligned records;
   returns whether the candidate list is still valid: no atom moved more than CAND_MOVE_LIMIT cskin
   and no radius changed since its build (same atoms)
------------------------------------------------------------------------- */

TBAGS_INLINE bool PairGranHertzRolling::pack_atoms()
{
  const int nall = atom->nlocal + atom->nghost;
  if (nall > npack) {
    free(packx);
    free(packv);
    npack = (nall + nall / 8 + 64) & ~1;    // even: whole 64-byte lines
    packx = static_cast<AtomX *>(aligned_alloc(64, sizeof(AtomX) * (size_t) npack));
    packv = static_cast<AtomV *>(aligned_alloc(64, sizeof(AtomV) * (size_t) npack));
    if (!packx || !packv) error->one(FLERR, "{}: out of memory packing {} atoms", STYLE, nall);
  }
  const double *x = atom->x[0];
  const double *v = atom->v[0];
  const double *omega = atom->omega[0];
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *type = atom->type;
  const int *mask = atom->mask;
  const int frzbit = freeze_group_bit;
  AtomX *__restrict px = packx;
  AtomV *__restrict pv = packv;
  // whole records as 4-double vectors: 3 values of atom i and one of i+1 loaded, the last
  // replaced (so the last atom, whose neighbour in memory may not exist, is done by itself)
  typedef double v4du __attribute__((vector_size(32), aligned(8), may_alias));
  typedef double v4da __attribute__((vector_size(32), may_alias));
  auto type_bits = [&](int i) {    // the type in the last 8 bytes of AtomV
    const unsigned long long b = (unsigned int) type[i];
    double d;
    memcpy(&d, &b, sizeof d);
    return d;
  };
  // the mass, negative for atoms in the fix freeze group
  auto signed_mass = [&](int i) { return (mask[i] & frzbit) ? -rmass[i] : rmass[i]; };
  static_assert(sizeof(AtomV) == 64 && offsetof(AtomV, type) == 56, "AtomV layout");
  // the candidate list's check (check_moves): the largest squared displacement since its build, and
  // whether a radius changed
  const bool check_moves = cand_nall == nall;
  const AtomX *__restrict ox = x0;
  double max_move2 = 0.0, max_dr2 = 0.0;
  // frz: a fix freeze group exists (else no mask read)
  auto pack_one = [&](int i, bool frz, bool ck) __attribute__((always_inline)) {
    v4du a = *reinterpret_cast<const v4du *>(x + 3 * i);
    a[3] = radius[i];
    *reinterpret_cast<v4da *>(&px[i]) = a;
    if (ck) {
      const v4d d = a - *reinterpret_cast<const v4da *>(&ox[i]), dd = d * d;
      const double m = dd[0] + dd[1] + dd[2];
      max_move2 = max_move2 > m ? max_move2 : m;
      max_dr2 = max_dr2 > dd[3] ? max_dr2 : dd[3];
    }
    v4du b = *reinterpret_cast<const v4du *>(v + 3 * i);
    b[3] = frz ? signed_mass(i) : rmass[i];
    reinterpret_cast<v4da *>(&pv[i])[0] = b;
    v4du c = *reinterpret_cast<const v4du *>(omega + 3 * i);
    c[3] = type_bits(i);
    reinterpret_cast<v4da *>(&pv[i])[1] = c;
  };
  if (frzbit) {
    if (check_moves) for (int i = 0; i < nall - 1; i++) pack_one(i, true, true);
    else for (int i = 0; i < nall - 1; i++) pack_one(i, true, false);
  } else {
    if (check_moves) for (int i = 0; i < nall - 1; i++) pack_one(i, false, true);
    else for (int i = 0; i < nall - 1; i++) pack_one(i, false, false);
  }
  if (nall > 0) {
    const int i = nall - 1;
    px[i].x[0] = x[3 * i];
    px[i].x[1] = x[3 * i + 1];
    px[i].x[2] = x[3 * i + 2];
    px[i].r = radius[i];
    pv[i].v[0] = v[3 * i];
    pv[i].v[1] = v[3 * i + 1];
    pv[i].v[2] = v[3 * i + 2];
    pv[i].m = signed_mass(i);
    pv[i].w[0] = omega[3 * i];
    pv[i].w[1] = omega[3 * i + 1];
    pv[i].w[2] = omega[3 * i + 2];
    pv[i].type = type[i];
    pv[i].pad = 0;
    if (check_moves) {
      const AtomX &o = ox[i];
      const double d0 = px[i].x[0] - o.x[0], d1 = px[i].x[1] - o.x[1], d2 = px[i].x[2] - o.x[2];
      const double m = d0 * d0 + d1 * d1 + d2 * d2;
      max_move2 = max_move2 > m ? max_move2 : m;
      if (px[i].r != o.r) max_dr2 = 1.0;
    }
  }
  // the candidate list still holds every pair that can touch
  return check_moves && max_move2 <= cand_lim2 && max_dr2 == 0.0;
}

/* ----------------------------------------------------------------------
   pass 1: walk the candidate list (or, when it must be rebuilt, the whole neighbor list,
   building it), reset the history of separated pairs and gather the touching ones into the
   batch; when full, run the law over it and scatter the result. Either walk visits every
   pair that can touch in neighbor-list order: the same contacts, the same bits.
   SPECIAL: the list may hold special-bond bits (else every factor is 1 and j needs no mask).
   TWIST: twisting sds (constants per contact: no SAME build of it).
------------------------------------------------------------------------- */

template <int ROLL, bool SPECIAL, bool TWIST> void PairGranHertzRolling::eval()
{
  // one set of constants for all contacts (law::batch_law's SAME), else per contact
  const law::Params *same = uniform_params();
  if (SPECIAL || TWIST || (same && ROLL != law::ROLLING_NONE && !(same->mur > 0.0))) same = nullptr;
#ifdef TBAGS_HAVE_AVX2_CLONE
  if (simd_avx2) {
    if constexpr (!SPECIAL && !TWIST)
      if (same) return walk_pairs_avx2<ROLL, false, true, false>(same);
    return walk_pairs_avx2<ROLL, SPECIAL, false, TWIST>(nullptr);
  }
#endif
  if constexpr (!SPECIAL && !TWIST)
    if (same) return walk_pairs<ROLL, false, true, false>(same);
  walk_pairs<ROLL, SPECIAL, false, TWIST>(nullptr);
}

// packing and gather built for AVX2 too (no FMA: the same bits as the baseline build)
template <int ROLL, bool SPECIAL, bool SAME, bool TWIST>
void PairGranHertzRolling::walk_pairs_avx2(const law::Params *same)
{
  walk_pairs<ROLL, SPECIAL, SAME, TWIST>(same);
}

// SAME: *same holds the constants of all contacts (else per contact, b.p)
template <int ROLL, bool SPECIAL, bool SAME, bool TWIST>
TBAGS_INLINE void PairGranHertzRolling::walk_pairs(const law::Params *same)
{
  if (list->inum == 0) return;
  const int nall = atom->nlocal + atom->nghost;
  // the candidate list holds every pair that can touch (else it is rebuilt in this pass)
  const bool integrate = update->setupflag == 0;    // the histories (not in a run's set-up)
  const double dt = update->dt;
  const bool valid = pack_atoms() && integrate && neighbor->lastcall == cand_lastcall;
  Batch &b = *batch;
  const AtomX *__restrict px = packx;
  const AtomV *__restrict pv = packv;
  const double *special_lj = force->special_lj;

  const int inum = list->inum;
  const int *ilist = list->ilist;
  int **firsttouch = fix_history->firstflag;
  double **firsthistory = fix_history->firstvalue;

  constexpr int NH = law::history_size(ROLL, TWIST);    // history doubles per contact
  // not inlined into the walk: it would cost the walk registers (4 instructions per contact-step)
  auto flush = [&](int n) __attribute__((noinline)) {
    hist_rows<NH>(b, n, simd_avx2);
    // the fast path; in the rare batch where a contact needs the full law, all again with it
    if (run_law<ROLL, SAME, SPECIAL, true, TWIST>(b, n, dt, limit_damping, simd_avx2, integrate, same)) {
      hist_rows<NH>(b, n, simd_avx2);
      run_law<ROLL, SAME, SPECIAL, false, TWIST>(b, n, dt, limit_damping, simd_avx2, integrate, same);
    }
    rows_hist<NH>(b, n, simd_avx2);
#ifdef TBAGS_HAVE_AVX2_CLONE
    if (simd_avx2 && !evflag) {
      if (force->newton_pair) scatter_avx2<1>(b, n, atom->f[0], atom->torque[0], atom->nlocal, atom->nmax);
      else scatter_avx2<0>(b, n, atom->f[0], atom->torque[0], atom->nlocal, atom->nmax);
      return;
    }
#endif
    if (force->newton_pair) evflag ? batch_scatter<NH, 1, 1>(n) : batch_scatter<NH, 1, 0>(n);
    else evflag ? batch_scatter<NH, 0, 1>(n) : batch_scatter<NH, 0, 0>(n);
  };

  int n = 0;
  // atom i's values for its contacts
  struct I {
    int i;
    v4d xi4;    // (x_i, -r_i): (x_i, -r_i) - (x_j, r_j) is dx and -(r_i + r_j)
    double vi0, vi1, vi2, wi0, wi1, wi2, mi;
    const law::Params *prow;
  };
  const v4d flip = {1.0, 1.0, 1.0, -1.0};
  auto atom_i = [&](int i) __attribute__((always_inline)) {
    const AtomV &ai = pv[i];
    return I{i, *reinterpret_cast<const v4d *>(&px[i]) * flip, ai.v[0], ai.v[1], ai.v[2],
             ai.w[0], ai.w[1], ai.w[2], ai.m, &law[ai.type * ntypes1]};
  };
  // r^2 as (dx0^2 + dx1^2) + dx2^2 < (r_i + r_j)^2 exactly, from d = (x_i, -r_i) - (x_j, r_j):
  // the same test as touching()
  auto touching = [](const v4d d) __attribute__((always_inline)) {
    const v4d dd = d * d;
    return dd[0] + dd[1] + dd[2] < dd[3];
  };
  auto forget = [](double *hist) __attribute__((always_inline)) {
    for (int k = 0; k < NH; k++) hist[k] = 0.0;
  };
  // neighbour j of i into the batch's next row n (taken by advancing n)
  auto put = [&](const I &c, int j, double factor_lj, double *hist, const v4d d)
      __attribute__((always_inline)) {
    __builtin_prefetch(hist, 1);    // read at the flush, written back after the law
    const AtomV &bj = pv[j];
    b.i[n] = c.i;
    b.j[n] = j;
    b.hist[n] = hist;
    if (!SAME) b.p[n] = &c.prow[bj.type];
    b.dx[0][n] = d[0];
    b.dx[1][n] = d[1];
    b.dx[2][n] = d[2];
    b.radi[n] = -c.xi4[3];
    b.radj[n] = px[j].r;
    b.mi[n] = c.mi;
    b.mj[n] = bj.m;
    if (SPECIAL) b.factor[n] = factor_lj;
    b.vr[0][n] = c.vi0 - bj.v[0];
    b.vr[1][n] = c.vi1 - bj.v[1];
    b.vr[2][n] = c.vi2 - bj.v[2];
    b.wi[0][n] = c.wi0;
    b.wi[1][n] = c.wi1;
    b.wi[2][n] = c.wi2;
    b.wj[0][n] = bj.w[0];
    b.wj[1][n] = bj.w[1];
    b.wj[2][n] = bj.w[2];
  };
  auto advance = [&](int by) __attribute__((always_inline)) {    // flushed when full
    if ((n += by) == Batch::N) {
      flush(n);
      n = 0;
    }
  };

  if (valid) {    // the candidates only, as one flat list (no branch per atom i)
    Cand *cd = cand.data();
    for (int k = 0; k < ncand; k++) {
      Cand &ck = cd[k];
      {    // the candidate 8 ahead (the list is padded past its end)
        const int jp = cd[k + 8].j & NEIGHMASK;
        __builtin_prefetch(&px[jp]);
        __builtin_prefetch(&pv[jp]);
      }
      const int jraw = ck.j;
      const int j = jraw & NEIGHMASK;
      const double factor_lj = SPECIAL ? special_lj[sbmask(jraw)] : 1.0;
      const I c = atom_i(ck.i);
      const v4d d = c.xi4 - *reinterpret_cast<const v4d *>(&px[j]);
      // the touch flag kept in the candidate (CAND_TOUCH), the list's set when it changes
      const bool t = touching(d);
      if (t != ((jraw & CAND_TOUCH) != 0)) {    // rare: starts touching, or separates (forget)
        ck.j = jraw ^ CAND_TOUCH;
        *ck.touch = t;
        if (!t) forget(ck.hist);
      }
      // every candidate written into the next row, kept if touching: no branch on the
      // distance test, which the predictor cannot learn
      put(c, j, factor_lj, ck.hist, d);
      advance(t);
    }
  } else {    // the whole neighbor list, building the candidate list
    const int *numneigh = list->numneigh;
    int **firstneigh = list->firstneigh;
    int nc = 0;
    for (int ii = 0; ii < inum; ii++) {
      const int i = ilist[ii];
      const I c = atom_i(i);
      const int *jlist = firstneigh[i];
      const int jnum = numneigh[i];
      int *touch = firsttouch[i];
      double *allhistory = firsthistory[i];
      if (cand.size() < (size_t) (nc + jnum)) cand.resize(2 * cand.size() + jnum);
      Cand *cd = cand.data();
      for (int jj = 0; jj < jnum; jj++) {
        const int jraw = jlist[jj];
        int j = jraw;
        double factor_lj = 1.0;
        if (SPECIAL) {
          factor_lj = special_lj[sbmask(j)];
          j &= NEIGHMASK;
          if (factor_lj == 0.0) continue;
        }
        __builtin_prefetch(&pv[j]);
        const v4d d = c.xi4 - *reinterpret_cast<const v4d *>(&px[j]);
        // a candidate: |dx| < r_i + r_j + cskin (else as a separated pair)
        const double rc = cskin - d[3];
        const bool candidate = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < rc * rc;
        double *hist = &allhistory[NH * jj];
        const bool t = touching(d);
        // written into the candidate list's and the batch's next entries, kept if a candidate,
        // if touching (no branch on either test; the flags change only when touching does)
        cd[nc] = Cand{i, t ? jraw | CAND_TOUCH : jraw, hist, &touch[jj]};
        nc += candidate;
        if (touch[jj] != t) {    // starts touching, or separates: forget
          touch[jj] = t;
          if (!t) forget(hist);
        }
        put(c, j, factor_lj, hist, d);
        advance(t);
      }
    }
    ncand = nc;
    if (cand.size() < (size_t) nc + 8) cand.resize(nc + 8);
    for (int k = nc; k < nc + 8; k++) cand[k] = Cand{0, 0, nullptr, nullptr};    // prefetched
    cand_nall = 0;    // no skin: the whole list every step (no positions kept)
    if (cskin > 0.0) {
      if (nx0 < nall) {
        free(x0);
        nx0 = npack;
        x0 = static_cast<AtomX *>(aligned_alloc(64, sizeof(AtomX) * (size_t) nx0));
        if (!x0) error->one(FLERR, "{}: out of memory for {} atoms", STYLE, nx0);
      }
      memcpy(x0, px, sizeof(AtomX) * (size_t) nall);
      cand_nall = nall;
    }
    cand_lastcall = neighbor->lastcall;
  }
  if (n) flush(n);
}

/* ----------------------------------------------------------------------
   pass 3: forces, torques and history back, in neighbor-list order
------------------------------------------------------------------------- */

template <int NH, int NEWTON, int EVFLAG> void PairGranHertzRolling::batch_scatter(int n)
{
  const Batch &b = *batch;
  double *__restrict f = atom->f[0];
  double *__restrict torque = atom->torque[0];
  const int nlocal = atom->nlocal;
  // f and torque of i summed in registers over its run of contacts: the same additions in the
  // same order as updating the arrays each time (j is never i)
  for (int l = 0; l < n;) {
    const int i = b.i[l];
    double *fi = f + 3 * i, *ti = torque + 3 * i;
    double fi0 = fi[0], fi1 = fi[1], fi2 = fi[2];
    double ti0 = ti[0], ti1 = ti[1], ti2 = ti[2];
    do {
      const int j = b.j[l];
      const double f0 = b.f[0][l], f1 = b.f[1][l], f2 = b.f[2][l];
      fi0 += f0;
      fi1 += f1;
      fi2 += f2;
      ti0 += b.ti[0][l];
      ti1 += b.ti[1][l];
      ti2 += b.ti[2][l];
      if (NEWTON || j < nlocal) {
        double *fj = f + 3 * j, *tj = torque + 3 * j;
        fj[0] -= f0;
        fj[1] -= f1;
        fj[2] -= f2;
        tj[0] += b.tj[0][l];
        tj[1] += b.tj[1][l];
        tj[2] += b.tj[2][l];
      }
      if (EVFLAG)
        ev_tally_xyz(i, j, nlocal, NEWTON, 0.0, 0.0, f0, f1, f2, b.dx[0][l], b.dx[1][l],
                     b.dx[2][l]);
    } while (++l < n && b.i[l] == i);
    fi[0] = fi0;
    fi[1] = fi1;
    fi[2] = fi2;
    ti[0] = ti0;
    ti[1] = ti1;
    ti[2] = ti2;
  }
}

