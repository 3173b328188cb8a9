/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   pair_style gran/hertz/rolling: thin adapter around law/contact_law.h
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_GRAN_HERTZ_ROLLING_H
#define LMP_PAIR_GRAN_HERTZ_ROLLING_H

#include "atom.h"
#include "pair.h"
#include "law/contact_law.h"

#include <memory>
#include <vector>

// the batch kernel is also built for AVX2 and picked at run time (GCC and Clang on x86-64)
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

namespace LAMMPS_NS {

class PairGranHertzRolling : public Pair {
 public:
  PairGranHertzRolling(class LAMMPS *);
  ~PairGranHertzRolling() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void write_data(FILE *) override;
  void write_data_all(FILE *) override;
  double single(int, int, int, int, double, double, double, double &) override;
  void transfer_history(double *, double *, int, int) override;
  double atom2cut(int) override;
  double radii2cut(double, double) override;
  void *extract(const char *, int &) override;
  double memory_usage() override;

  // per-type material and per-pair coefficients (public for the plate fix)
  const tbags::contact::Params &params(int i, int j) const { return law[i * (ntypes1) + j]; }
  double material_E(int i) const { return Emod[i]; }
  double material_nu(int i) const { return poiss[i]; }
  int rolling_model() const { return rolling; }
  bool damping_limited() const { return limit_damping; }

  // Contacts gathered from the neighbor list in structure-of-arrays form (one row per value,
  // one column per contact), so the law runs over them in SIMD lanes, then scattered back in
  // neighbor-list order (forces sum in the same order as a plain loop).
  struct alignas(64) Batch {
    static constexpr int N = 32;
    int i[N], j[N];
    double *hist[N];
    const tbags::contact::Params *p[N];
    double dx[3][N], radi[N], radj[N], mi[N], mj[N], factor[N];    // m < 0: frozen
    double vr[3][N], wi[3][N], wj[3][N], h[6][N];
    double f[3][N], ti[3][N], tj[3][N];
    // from the law's normal loop to its tangential and rolling loops
    double n[3][N], vt[3][N], a[N], sqma[N], fn[N], delta[N], reff[N];
    double meff[N], fne[N], vnnr[N];    // from the normal loop to the damping
  };

 protected:
  int rolling;            // tbags::contact::Rolling
  bool limit_damping;
  int size_history;
  int history_model;    // the rolling model the history store was made for (-1: none yet)
  int ntypes1;            // ntypes + 1
  int freeze_group_bit;
  int neighprev;

  // per type (1..ntypes)
  double *Emod, *poiss;
  int *matflag;
  double *maxrad;
  // per type pair (explicit values; -1 = mix from the diagonal)
  double **mu, **mur, **cor;
  std::vector<tbags::contact::Params> law;    // flat [i*(ntypes+1)+j]

  class FixDummy *fix_dummy;
  class FixNeighHistory *fix_history;

  std::unique_ptr<Batch> batch;

  // Per-atom data of the kernel packed once per compute() (local and ghost atoms): the distance
  // test reads one 32-byte record, a touching neighbour one 64-byte line more, instead of
  // seven separate arrays.
  struct alignas(32) AtomX {
    double x[3], r;
  };
  struct alignas(64) AtomV {
    double v[3], m, w[3];    // m < 0: in the fix freeze group (m* is the other's mass)
    int type, pad;
  };
  AtomX *packx;
  AtomV *packv;
  int npack;    // capacity
  inline bool pack_atoms();

  // Candidate list: the pairs of the neighbor list closer than r_i + r_j + cskin, as
  // (i, raw j, its history and touch flag), in list order, built by a full pass over the list;
  // pairs left out cannot touch while no atom has moved cskin/2 (or changed radius) since,
  // so each step visits only these. Rebuilt at each neighbor list build, run setup, or when
  // an atom has moved that far (pack_atoms() compares with the positions x0 at the build).
  static constexpr int CAND_TOUCH = 1 << HISTBITS;    // in Cand::j: touching (else 0)
  struct Cand {
    int i, j;    // j as in the list (no history bit there), CAND_TOUCH added
    double *hist;
    int *touch;
  };
  std::vector<Cand> cand;         // ncand, then 8 for the prefetch
  int ncand;
  AtomX *x0;                      // positions and radii at the build
  int nx0;                        // capacity of x0
  int cand_nall;                  // atoms (local + ghost) at the build, 0: no valid list
  bigint cand_lastcall;           // neighbor->lastcall at the build
  double cskin;                   // the candidate skin (distance)
  double cand_lim2;               // (cskin/2)^2 less a margin: squared displacement that forces a rebuild

  void allocate();
  void choose_kernel();
  template <bool SB> void eval_rolling(bool update_history);    // eval() for the rolling model
  template <int ROLL, bool UPDATE, bool SB> void eval();
  template <int ROLL, bool UPDATE, bool SB, bool UNI>
  TBAGS_TARGET_AVX2 void eval_avx2(const tbags::contact::Params *puni);
  template <int ROLL, bool UPDATE, bool SB, bool UNI>
  inline void eval_body(const tbags::contact::Params *puni);
  // the batch law's build: keyword 'kernel auto|avx2|baseline'; simd_avx2 (1: AVX2, 0: baseline)
  // is the one init_style chose and logged, an int so that extract("kernel_avx2") can give it
  enum { KERNEL_AUTO = 0, KERNEL_AVX2 = 1, KERNEL_BASELINE = 2 };
  int kernel_choice;
  int simd_avx2;
  int simd_logged;              // the kernel last logged (-1: none yet)
  double contact_skin;          // keyword 'contact_skin f': candidate skin, fraction of the neighbor skin
  const tbags::contact::Params *uniform_params() const;
  template <int NH, int NEWTON, int EVFLAG>
  TBAGS_NOINLINE_NO_SLP void batch_scatter(int n);
  // geometry and kinematics of the pair i-j for the law (dx = x_i - x_j, already computed);
  // m* is the other particle's mass when one of them is frozen (fix freeze)
  void set_contact(int i, int j, double *dx, double rsq, double radsum,
                   tbags::contact::Contact &c) const
  {
    const double *rmass = atom->rmass;
    c.radi = atom->radius[i];
    c.radj = atom->radius[j];
    tbags::contact::effective(rmass[i], rmass[j], c.radi, c.radj, c.meff, c.reff);
    if (atom->mask[i] & freeze_group_bit) c.meff = rmass[j];
    if (atom->mask[j] & freeze_group_bit) c.meff = rmass[i];
    c.dx = dx;
    c.rsq = rsq;
    c.radsum = radsum;
    c.vi = atom->v[i];
    c.vj = atom->v[j];
    c.wi = atom->omega[i];
    c.wj = atom->omega[j];
  }
};

}    // namespace LAMMPS_NS

#endif
