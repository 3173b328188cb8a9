/* -*- c++ -*- ----------------------------------------------------------
   T-BAGS DEM toolkit (tbags plugin for LAMMPS)
   pair_style gran/hertz/rolling: thin adapter around law/contact_law.h
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_GRAN_HERTZ_ROLLING_H
#define LMP_PAIR_GRAN_HERTZ_ROLLING_H

#include "atom.h"
#include "pair.h"
#include "law/contact_chain.h"
#include "simd_target.h"

#include <memory>
#include <vector>

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
  bool rolling_radius_mean() const { return roll_mean; }
  bool twisting_on() const { return twisting; }

  // the touching pairs, gathered for the batch law (law/contact_chain.h)
  using Batch = tbags::contact::Batch;
  static constexpr const char *STYLE = "Pair style gran/hertz/rolling";

 protected:
  int rolling;            // tbags::contact::Rolling
  bool limit_damping;
  bool roll_mean;         // rolling_radius mean: (Ri+Rj)/2, else R* (law::rolling_radius())
  bool twisting;          // twisting sds (law::TwistingSds), else none
  int size_history;
  int history_model;    // history_key() the history store was made for (-1: none yet)
  int history_key() const { return rolling + (twisting ? 8 : 0); }
  int ntypes1;            // ntypes + 1
  int freeze_group_bit;
  int neighprev;

  // per type (1..ntypes)
  double *Emod, *poiss;
  int *matflag;
  double *maxrad;
  // per type pair (explicit values; -1 = mix from the diagonal)
  double **mu, **mur, **cor;
  double **ktw, **ctw, **mutw;    // twisting sds: stiffness, damping, cap's lever (m)
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
  // compute() in pair_gran_hertz_rolling_kernel.cpp: eval_rolling() for twisting, eval() for the
  // rolling model and the special-bond factors, then walk_pairs() for the constants (one set or per type pair) and
  // the build (AVX2 or baseline)
  template <bool TWIST> void eval_rolling(bool special);
  template <int ROLL, bool SPECIAL, bool TWIST> void eval();
  template <int ROLL, bool SPECIAL, bool SAME, bool TWIST>
  TBAGS_TARGET_AVX2 void walk_pairs_avx2(const tbags::contact::Params *same);
  template <int ROLL, bool SPECIAL, bool SAME, bool TWIST>
  inline void walk_pairs(const tbags::contact::Params *same);
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
  void set_contact(int i, int j, double *dx, tbags::contact::Contact &c) const
  {
    const double *rmass = atom->rmass;
    c.radi = atom->radius[i];
    c.radj = atom->radius[j];
    const double mi = (atom->mask[i] & freeze_group_bit) ? -rmass[i] : rmass[i];
    const double mj = (atom->mask[j] & freeze_group_bit) ? -rmass[j] : rmass[j];
    tbags::contact::effective_frozen(mi, mj, c.radi, c.radj, c.meff, c.reff);
    c.dx = dx;
    c.vi = atom->v[i];
    c.vj = atom->v[j];
    c.wi = atom->omega[i];
    c.wj = atom->omega[j];
  }
};

}    // namespace LAMMPS_NS

#endif
